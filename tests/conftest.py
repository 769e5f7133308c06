"""Session-wide test settings."""

from __future__ import annotations

import os

import pytest


@pytest.fixture(autouse=True, scope="session")
def _own_trust_dir(tmp_path_factory: pytest.TempPathFactory) -> None:
    """The digests of the policies trained by the tests go to a folder of the test session, not
    to the user's (``ship_gym.envs.policy_trust``); worker processes inherit it."""
    os.environ["SHIP_GYM_TRUST_DIR"] = str(tmp_path_factory.mktemp("trusted_policies"))
