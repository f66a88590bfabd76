#pragma once
// `headlight render`: jobs (job_file.hpp) from the command line and job
// files, sharded, resumable, rendered by one context and one renderer,
// written on a worker thread while the next view renders. Every job holds
// its output folder's lock (io/folder_lock.hpp) from before its render
// until its set is written. docs/BATCH.md is the user's guide.
#include "cli_options.hpp"

namespace headlight::cli {

// `render`: plan (batch_plan.hpp), run, report (batch.cpp). A single render (one scene, no
// views, cameras, job files or shards) is a batch of one whose errors are
// the command's (exit 1, or 2 for bad settings); a batch returns 0, or 1
// when any job failed.
int runRender(const RenderCommand& command);

}  // namespace headlight::cli
