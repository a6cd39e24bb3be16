"""Debian's Chromium, driven by playwright (never `playwright install`), for the browser tests.

Without playwright or Chromium a browser test is skipped, except in CI (CI=true), where .ci/run
installs Chromium and the test must run.
"""

import os
import shutil
from contextlib import contextmanager
from pathlib import Path

import pytest

ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update"]


def executable() -> str | None:
    for candidate in ("/usr/bin/chromium", shutil.which("chromium"), shutil.which("chromium-browser")):
        if candidate and Path(candidate).is_file():
            return candidate
    return None


@contextmanager
def chromium():
    """A launched headless Chromium (playwright Browser), or a skip (a failure in CI)."""
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        reason = "the playwright package is not installed (pip install -e '.[test]')"
    else:
        path = executable()
        if path is not None:
            with sync_playwright() as p:
                browser = p.chromium.launch(executable_path=path, args=ARGS)
                try:
                    yield browser
                finally:
                    browser.close()
            return
        reason = "no Chromium found (apt-get install chromium)"
    if os.environ.get("CI"):
        pytest.fail(f"CI must run the browser tests: {reason}")
    pytest.skip(reason)
