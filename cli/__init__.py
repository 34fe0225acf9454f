"""`flexmm`, the command line: the top layer (paper eq. -> derivation -> generated ->
numerics -> scenes -> cli).

One module per command; each parses its options, calls numerics (or the scenes), formats
what it prints and writes its files (``point.json``, ``point.png``, ``map.zarr``, ...).
Nothing below imports this package.

Public API
----------
main(argv=None) -> int      run ``flexmm`` with ``argv`` (default ``sys.argv[1:]``); the
                            exit code: 0 ok, 2 bad input or file system, 130 / 143 interrupted

Modules
-------
app             the dispatch, exit codes and interrupt lines (the parser: ``_parser``)
coefficients    ``flexmm coefficients``
table           ``flexmm table``
point           ``flexmm point``
soliton         ``flexmm soliton``
map             ``flexmm map``
"""

from .app import main

__all__ = ["main"]
