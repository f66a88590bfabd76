#pragma once
// `headlight render`: jobs (job_file.hpp) from the command line and job
// files, sharded, resumable, rendered by one context and one renderer,
// written on a worker thread while the next view renders. Every job holds
// its output folder's lock (io/folder_lock.hpp) from before its render
// until its set is written. docs/BATCH.md is the user's guide.
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cli_options.hpp"
#include "job_file.hpp"

namespace headlight::cli {

// True when `job.outDir` holds a complete set (checkFrameSet) written for
// the same job hash (with `environment`, the --environment file: jobHash):
// --resume skips it.
bool jobAlreadyDone(const Job& job, const OutputOptions& output, const std::string& environment = {});

// Why a job may not write into its folder, or "" when it may: the folder
// holds the scene file (out = the scene's folder), or, without `force`, a
// file with a target's name (lit.exr, frame.json, ...) that no earlier
// Headlight set there listed (a user's own file, which writing would replace).
std::string outputFolderRefusal(const Job& job, bool force);

// The files among `names` that `folder` holds and `ours` does not recognise
// as an earlier `writer`'s (e.g. "headlight reference"), as a refusal naming
// them; "" when there are none or `force`. What render, reference and bench
// write over, each with its own rule for "ours".
std::string foreignFilesRefusal(const std::filesystem::path& folder, std::span<const std::string> names,
                                const std::function<bool(const std::filesystem::path&)>& ours, std::string_view writer,
                                bool force);

// `render`: plan, run, report (batch.cpp). A single render (one scene, no
// views, cameras, job files or shards) is a batch of one whose errors are
// the command's (exit 1, or 2 for bad settings); a batch returns 0, or 1
// when any job failed.
int runRender(const RenderCommand& command);

}  // namespace headlight::cli
