# -----------------------------------------------------------------------------
# GENERATED FILE - DO NOT EDIT BY HAND.
# Written by `make derive` (python -m derivation).
# -----------------------------------------------------------------------------
"""Generated code of the built-in lattice models (energy/models/*.toml)."""
