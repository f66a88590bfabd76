#pragma once
// Image comparison for regression suites (headlight diff), following
// OpenImageIO idiff's semantics: warn and fail levels, a percent-of-pixels
// allowance and a hard per-pixel cap. Written by the diff work (issue 4).
