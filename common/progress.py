"""The progress bar class: tqdm's notebook widget where Jupyter can draw it, else the
terminal bar.

``tqdm.auto`` picks the notebook widget in any IPython kernel and, where ipywidgets is not
installed (the docs build, a bare Jupyter), warns "IProgress not found" with the file path
of the machine it runs on, then falls back to the terminal bar anyway: here the fallback
comes first and nothing is warned.
"""

from __future__ import annotations


def progress_class():
    """``tqdm.auto.tqdm`` where ipywidgets is importable, else ``tqdm.std.tqdm``."""
    try:
        import ipywidgets  # noqa: F401
    except ImportError:
        from tqdm.std import tqdm
        return tqdm
    from tqdm.auto import tqdm
    return tqdm
