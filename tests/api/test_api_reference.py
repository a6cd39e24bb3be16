"""docs/api.md is generated from the docstrings (docs/make_api_reference.py) and kept up to date."""

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_the_api_reference_says_what_the_docstrings_say():
    done = subprocess.run(
        [sys.executable, str(ROOT / "docs" / "make_api_reference.py"), "--check"],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr


def test_every_public_name_is_in_the_reference():
    import ev3sim2d

    text = (ROOT / "docs" / "api.md").read_text(encoding="utf-8")
    for name in ev3sim2d.__all__:
        assert f"`{name}" in text or f"class `{name}`" in text, name
