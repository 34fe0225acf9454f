"""Lattice simulator of eq. `norm` (filled in by the simulator issue)."""
