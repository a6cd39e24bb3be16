"""Debian's Chromium, driven by playwright (never `playwright install`), for the browser tests.

Without playwright or Chromium a browser test is skipped, except in CI (CI=true), where .ci/run
installs Chromium and the test must run.  Where there is no Chromium (Windows, macOS: the OS matrix
of .github/workflows/tests.yml), an installed Google Chrome, Chromium's own build, does.
"""

import os
import shutil
from contextlib import contextmanager
from pathlib import Path

import pytest

ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update"]


def executable() -> str | None:
    for candidate in (
        "/usr/bin/chromium",
        shutil.which("chromium"),
        shutil.which("chromium-browser"),
        *_chrome(),
    ):
        if candidate and Path(candidate).is_file():
            return candidate
    return None


def _chrome() -> list[str]:
    """Where Google Chrome installs itself on macOS and on Windows."""
    found = ["/Applications/Google Chrome.app/Contents/MacOS/Google Chrome"]
    for folder in ("PROGRAMFILES", "PROGRAMFILES(X86)", "LOCALAPPDATA"):
        if os.environ.get(folder):
            found.append(os.path.join(os.environ[folder], "Google", "Chrome", "Application", "chrome.exe"))
    return found


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
