"""Benchmarks and stress tests (bench/README.md): run as modules from the repository root,
``python -m bench.<script>`` (what `make bench` / `make stress` do), so that the scripts
import each other as ``bench.<script>``. Results go to out/bench/ unless ``--update``."""
