#!/usr/bin/python3
"""N Python threads, each with its own headlight.Renderer, rendering at once.

  LP_NUM_THREADS=2 PYTHONPATH=build/python /usr/bin/python3 tools/thread_stress.py osmesa,osmesa,osmesa

One thread per backend named; each makes a renderer, sets builtin:cornell and
renders 15 frames of 64x48. Prints "ok" (exit 0), or crashes: docs/EMBEDDING.md
("Threads") counts the runs that crashed before the backend lock (ContextAccess::lockBackend) existed.
"""
import sys
import threading

import headlight


def work(backend):
    renderer = headlight.Renderer(backend=backend)
    renderer.set_scene("builtin:cornell")
    for _ in range(15):
        renderer.render(width=64, height=48, ssgi_samples=8)["lit"]


backends = sys.argv[1].split(",") if len(sys.argv) > 1 else ["egl", "osmesa"]
threads = [threading.Thread(target=work, args=(b,)) for b in backends]
for t in threads:
    t.start()
for t in threads:
    t.join()
print("ok", backends)
