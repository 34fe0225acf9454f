"""The code a result depends on, as a hash: keys the scene cache and is stored with maps."""

from __future__ import annotations

import hashlib
from pathlib import Path


def source_hash(*roots) -> str:
    """Hash of every ``.py`` file under the folders ``roots`` (package roots), found by
    walking them: computed, never listed, so a new or changed module cannot be missed."""
    h = hashlib.sha256()
    for root in roots:
        root = Path(root)
        for f in sorted(root.rglob("*.py")):
            h.update(f"{root.name}/{f.relative_to(root).as_posix()}".encode() + b"\0"
                     + f.read_bytes())
    return h.hexdigest()[:16]


def _code_version() -> str:
    """The code a simulated or theoretical number depends on: all of numerics, the
    generated closed forms and the paper's numbers."""
    import common
    import generated

    numerics_root = Path(__file__).resolve().parents[1]
    return source_hash(numerics_root, Path(generated.__file__).parent,
                       Path(common.__file__).parent)


#: Identifies the simulator's code (keys the scene cache): a hash of its sources, so any
#: change that may alter simulated numbers invalidates cached runs by itself.
SIMULATOR_VERSION = _code_version()
