"""A flexure mechanism described once, as rigid bodies joined by flexures, and the models
derived from it: the continuum (draw.py), the beam model (beams.py) and its outline for
manufacture (export.py)."""
from .description import Body, Leaf, Mechanism, Notch
from .draw import draw, mesh_mechanism

__all__ = ["Body", "Leaf", "Mechanism", "Notch", "draw", "mesh_mechanism"]
