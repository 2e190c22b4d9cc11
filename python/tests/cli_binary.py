"""The ``stickslip`` binary for the tests: found at ``$STICKSLIP_BIN``,
else ``$CARGO_TARGET_DIR/release/stickslip``, else
``target/release/stickslip`` at the repository's top (build it with
``cargo build --release``). Without it the tests fail: they never skip.
"""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def binary() -> Path:
    if os.environ.get("STICKSLIP_BIN"):
        path = Path(os.environ["STICKSLIP_BIN"])
    else:
        target = Path(os.environ.get("CARGO_TARGET_DIR") or ROOT / "target")
        path = target / "release" / "stickslip"
    assert path.is_file(), (
        f"the stickslip binary is not at {path}: run `cargo build --release` "
        "(or set STICKSLIP_BIN)"
    )
    return path


def cli(*args: object, ok: bool = True) -> subprocess.CompletedProcess:
    p = subprocess.run(
        [str(binary()), *map(str, args)], capture_output=True, text=True, timeout=600
    )
    if ok:
        assert p.returncode == 0, p.stderr
    return p
