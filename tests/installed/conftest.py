"""The installed package, once a session: the venv .ci/run made, else one made here."""

import pytest

from tests.installed import installed_venv


@pytest.fixture(scope="session")
def installed(tmp_path_factory) -> installed_venv.InstalledVenv:
    return installed_venv.from_environment() or installed_venv.make(tmp_path_factory.mktemp("installed"))


@pytest.fixture
def user_folder(tmp_path):
    """A folder of the user's, not the checkout."""
    folder = tmp_path / "work"
    folder.mkdir()
    return folder
