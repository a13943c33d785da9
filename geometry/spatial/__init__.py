"""Spatial flexure mechanisms: 3-D bodies (boxes, cylinders, prisms) joined by wire and leaf
flexures, described once (description.py, tables.py for model files) and meshed as one
fused solid (continuum.py); the exact-constraint analysis is studies/spatial."""
