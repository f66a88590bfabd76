// Embree reference: written by the ground-truth work (issue 3).
