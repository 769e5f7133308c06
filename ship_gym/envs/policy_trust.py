"""Which saved policies may be loaded: a stable-baselines3 model file runs code when it is read.

An SB3 ``model.zip`` holds pickled Python objects (its ``:serialized:`` entries: spaces,
schedules) and a ``VecNormalize`` ``.pkl`` file is a pickle: loading either can execute any code
its author put in it. The package therefore loads a model only when one of these holds
(:func:`check_policy_trust`):

* the caller opts in (``trusted=True`` in the API, ``--trust-policy`` on the command line);
* its SHA-256 equals a digest the caller recorded and passes (``expected_sha256``; what a
  campaign's policy cells check in every worker);
* its SHA-256 was recorded when this installation trained it: :func:`record_trusted_policy`
  (called by :func:`ship_gym.agents.train.train`) writes one empty-named file per digest in the
  trust folder (:func:`trust_dir`: ``$SHIP_GYM_TRUST_DIR``, else
  ``$XDG_DATA_HOME/ship_gym/trusted_policies``, else ``~/.local/share/ship_gym/trusted_policies``);
* its SHA-256 is one of the policies shipped with the package (``data/shipped_policies.json``:
  ``docs/benchmarks/policies``).

Observation statistics are saved as ``vecnormalize.npz`` (plain arrays, read with
``allow_pickle=False``): they need no trust. See ``docs/security.md``.
"""

from __future__ import annotations

import functools
import hashlib
import json
import os
from importlib import resources
from pathlib import Path

__all__ = [
    "TRUST_DIR_ENV",
    "UntrustedPolicyError",
    "check_policy_trust",
    "is_trusted_digest",
    "record_trusted_policy",
    "sha256_hex",
    "shipped_policy_digests",
    "trust_dir",
]

TRUST_DIR_ENV = "SHIP_GYM_TRUST_DIR"
"""Environment variable naming the folder of the digests of the policies trained here."""

_SHIPPED_FILE = "shipped_policies.json"


class UntrustedPolicyError(ValueError):
    """A policy file that would run code when loaded, and that nobody vouched for."""


def sha256_hex(data: bytes) -> str:
    """SHA-256 of ``data`` as 64 hexadecimal digits."""
    return hashlib.sha256(data).hexdigest()


def trust_dir() -> Path:
    """The folder holding one file per SHA-256 of a policy this installation trained."""
    explicit = os.environ.get(TRUST_DIR_ENV)
    if explicit:
        return Path(explicit).expanduser()
    base = os.environ.get("XDG_DATA_HOME") or str(Path.home() / ".local" / "share")
    return Path(base) / "ship_gym" / "trusted_policies"


@functools.cache
def shipped_policy_digests() -> dict[str, str]:
    """SHA-256 → name of each ``model.zip`` shipped in ``docs/benchmarks/policies``."""
    text = resources.files("ship_gym.data").joinpath(_SHIPPED_FILE).read_text(encoding="utf-8")
    return {str(k): str(v) for k, v in json.loads(text).items()}


def _valid_digest(digest: str) -> bool:
    return len(digest) == 64 and all(c in "0123456789abcdef" for c in digest)


def is_trusted_digest(digest: str) -> bool:
    """True when ``digest`` is a shipped policy's or was recorded by a training run here."""
    if not _valid_digest(digest):
        return False
    if digest in shipped_policy_digests():
        return True
    return (trust_dir() / digest).is_file()


def record_trusted_policy(path: str | os.PathLike[str]) -> str | None:
    """Record the SHA-256 of a model file this installation wrote (a training run's).

    Parameters
    ----------
    path : str or path-like
        The ``model.zip`` just saved.

    Returns
    -------
    str or None
        The digest, or None when the trust folder cannot be written (then loading the model
        needs ``trusted=True`` / ``--trust-policy``; a warning says so).
    """
    p = Path(path)
    digest = sha256_hex(p.read_bytes())
    folder = trust_dir()
    try:
        folder.mkdir(parents=True, exist_ok=True)
        (folder / digest).write_text(str(p.resolve()) + "\n", encoding="utf-8")
    except OSError as exc:
        import warnings

        warnings.warn(
            f"could not record the digest of {p} in {folder} ({exc}); loading it will need "
            "--trust-policy (ship-gym evaluate) or trusted=True",
            stacklevel=2,
        )
        return None
    return digest


def check_policy_trust(
    data: bytes,
    path: str | os.PathLike[str],
    *,
    trusted: bool = False,
    expected_sha256: str | None = None,
    what: str = "model",
) -> str:
    """Refuse a model file that would run code unless it is trusted (module docstring).

    Parameters
    ----------
    data : bytes
        The file's content (the bytes that will be loaded: no second read).
    path : str or path-like
        Its path (for the messages).
    trusted : bool
        The caller's explicit opt-in.
    expected_sha256 : str, optional
        A digest recorded earlier (a campaign's); the file must match it.
    what : str
        What the file is, for the message.

    Returns
    -------
    str
        The file's SHA-256.

    Raises
    ------
    UntrustedPolicyError
        A digest mismatch, or a file neither trusted nor known.
    """
    digest = sha256_hex(data)
    if expected_sha256 is not None:
        if digest != expected_sha256:
            raise UntrustedPolicyError(
                f"{path}: SHA-256 {digest} differs from the digest {expected_sha256} recorded "
                f"for this {what}; the file changed since it was checked, expected the same file"
            )
        return digest
    if trusted or is_trusted_digest(digest):
        return digest
    raise UntrustedPolicyError(
        f"{path}: refusing to load this {what} (SHA-256 {digest}): it was neither trained by "
        "this installation nor shipped with ship_gym, and loading a stable-baselines3 file runs "
        "any code its author put in it (pickle). If you trust where it came from, pass "
        "--trust-policy (ship-gym evaluate, campaign run) or trusted=True; see docs/security.md"
    )
