"""Analyses of spatial flexure mechanisms (geometry/spatial): the exact-constraint analysis
of their idealised flexures (exact_constraint.py)."""
