#!/bin/sh
# Usage: generate.sh GLAD OUT_H OUT_C
# Runs glad into a scratch folder and copies the two files meson tracks.
#
# glad runs with --mx: the entry points live in a GladGLContext table that
# each headlight::Context owns, not in process-wide globals. One global table
# is wrong as soon as two threads render through different backends: on
# Debian's glvnd, eglGetProcAddress hands out libGLdispatch stubs and
# OSMesaGetProcAddress libglapi stubs, and each only dispatches to its own
# backend's current context. So that the code keeps calling glFoo(...), the
# header gets, appended, a thread-local "current table" (set by
# Context::makeCurrent) and one macro per entry point that calls through it:
#   #define glFoo (gladGetCurrentGLContext()->Foo)
# (what upstream glad 2's --mx-global does; Debian 12's glad lacks that flag).
set -eu
glad="$1"; out_h="$2"; out_c="$3"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$glad" --reproducible --quiet --api gl:core=4.5 --extensions GL_KHR_debug \
  --out-path "$tmp" c --mx >/dev/null
header="$tmp/include/glad/gl.h"
{
  cat "$header"
  cat <<'EOT'

/* Appended by subprojects/glad/generate.sh: the calling thread's table. */
#ifndef GLAD_GL_CURRENT_TABLE_H_
#define GLAD_GL_CURRENT_TABLE_H_
#ifdef __cplusplus
extern "C" {
#endif
/* The table GL calls on this thread go through; NULL until one is set. */
GladGLContext *gladGetCurrentGLContext(void);
void gladSetCurrentGLContext(GladGLContext *context);
#ifdef __cplusplus
}
#endif
EOT
  # One macro per member of the table: entry points (glFoo) and the
  # version/extension flags (GLAD_GL_FOO).
  awk '/^typedef struct GladGLContext \{/ {inside = 1; next}
       /^\} GladGLContext;/ {inside = 0}
       inside && $1 ~ /^PFNGL/ { name = $2; sub(/;$/, "", name);
         printf "#define gl%s (gladGetCurrentGLContext()->%s)\n", name, name }
       inside && $1 == "int" { name = $2; sub(/;$/, "", name);
         printf "#define GLAD_GL_%s (gladGetCurrentGLContext()->%s)\n", name, name }' "$header"
  echo '#endif'
} > "$out_h"
{
  cat "$tmp/src/gl.c"
  cat <<'EOT'

/* Appended by subprojects/glad/generate.sh (see gl.h). */
static _Thread_local GladGLContext *glad_current_gl_context = NULL;
GladGLContext *gladGetCurrentGLContext(void) { return glad_current_gl_context; }
void gladSetCurrentGLContext(GladGLContext *context) { glad_current_gl_context = context; }
EOT
} > "$out_c"
