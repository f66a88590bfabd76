#pragma once
// What the library (and its tests) need of a Context beyond the public
// class: the backend lock and the count of unreported GL errors.
#include <cstddef>
#include <mutex>

#include "headlight/context.hpp"

namespace headlight::detail {

struct ContextAccess {
  // One lock per backend, held by every Renderer call that touches the GL
  // (and by context creation and destruction): Mesa 22.3's llvmpipe crashed
  // inside the driver when two contexts of the same backend drew at the same
  // time on different threads (docs/EMBEDDING.md, "Threads"). Renderers of
  // one backend on several threads are therefore safe but take turns; an EGL
  // and an OSMesa renderer still run at the same time.
  [[nodiscard]] static std::unique_lock<std::mutex> lockBackend(const Context& context);
  // Errors collected so far and not yet reported by checkErrors (tests check
  // that a test left none).
  static std::size_t pendingErrorCount(const Context& context);
};

}  // namespace headlight::detail
