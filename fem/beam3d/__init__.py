"""flexfem.fem.beam3d: a spatial (6 DOFs per node) co-rotational beam model."""
