"""Hand-written physics: NumPy only, no pygame (particles, forces, integrators, constraints, cloth)."""
