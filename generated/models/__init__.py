"""Generated code of the built-in lattice models (energy/models/*.toml),
written by `make derive`; do not edit by hand."""
