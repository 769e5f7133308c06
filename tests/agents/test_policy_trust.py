"""The trust boundary of policy files (issue #35): a crafted ``model.zip`` or
``vecnormalize.pkl`` whose payload would write a marker file never runs without the opt-in."""

from __future__ import annotations

import base64
import hashlib
import json
import pickle
import shutil
import zipfile
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("stable_baselines3")

from ship_gym.cli import main
from ship_gym.envs.policy_trust import (
    UntrustedPolicyError,
    check_policy_trust,
    is_trusted_digest,
    shipped_policy_digests,
)
from ship_gym.envs.saved_policies import load_policy, read_obs_normalizer, save_obs_normalizer

ROOT = Path(__file__).parents[2]
SHIPPED = ROOT / "docs" / "benchmarks" / "policies"
ROLL = SHIPPED / "RollStabilization" / "ppo_roll_stabilization"


class _Payload:
    """Unpickling this writes ``marker`` (what an attacker's code would do, harmlessly)."""

    def __init__(self, marker: Path) -> None:
        self.marker = marker

    def __reduce__(self):
        return (exec, (f"open({str(self.marker)!r}, 'w').write('ran')",))


def _crafted_model(folder: Path, marker: Path, env_id: str = "ship_gym/RollStabilization-v2"):
    """A ``model.zip`` whose ``data`` holds a ``:serialized:`` entry (SB3 unpickles those)."""
    folder.mkdir(parents=True, exist_ok=True)
    payload = base64.b64encode(pickle.dumps(_Payload(marker))).decode()
    data = {"observation_space": {":type:": "<class 'x'>", ":serialized:": payload}}
    with zipfile.ZipFile(folder / "model.zip", "w") as zf:
        zf.writestr("data", json.dumps(data))
    (folder / "config.toml").write_text(
        f'[env]\nid = "{env_id}"\n\n[algorithm]\nname = "PPO"\n', encoding="utf-8"
    )
    return folder


def test_the_crafted_model_really_runs_its_payload_when_trusted(tmp_path):
    # the control: with the opt-in, SB3 unpickles the entry (then fails on the rest)
    marker = tmp_path / "marker"
    run = _crafted_model(tmp_path / "run", marker)
    with pytest.raises(ValueError):
        load_policy(run, trusted=True)
    assert marker.read_text() == "ran"


def test_a_crafted_model_zip_does_not_run_without_the_opt_in(tmp_path):
    marker = tmp_path / "marker"
    run = _crafted_model(tmp_path / "run", marker)
    with pytest.raises(UntrustedPolicyError, match=r"model\.zip: refusing to load .*--trust-pol"):
        load_policy(run)
    assert not marker.exists()


def test_a_crafted_vecnormalize_pickle_beside_a_shipped_model_does_not_run(tmp_path):
    marker = tmp_path / "marker"
    run = tmp_path / "run"
    run.mkdir()
    for name in ("model.zip", "config.toml"):
        shutil.copy(ROLL / name, run / name)
    (run / "vecnormalize.pkl").write_bytes(pickle.dumps(_Payload(marker)))
    with pytest.raises(UntrustedPolicyError, match=r"vecnormalize\.pkl: .*pickle.*--trust-policy"):
        load_policy(run)
    assert not marker.exists()
    # with the opt-in it is read (and found not to be a VecNormalize), naming the file
    with pytest.raises(ValueError, match=r"vecnormalize\.pkl: holds a NoneType, not a VecNorm"):
        load_policy(run, trusted=True)
    assert marker.exists()


def test_evaluate_refuses_a_crafted_model_without_trust_policy(tmp_path, capsys):
    marker = tmp_path / "marker"
    run = _crafted_model(tmp_path / "run", marker)
    argv = ["evaluate", "--env", "ship_gym/RollStabilization-v2", "--policies", f"model:{run}",
            "--episodes", "1", "--out", str(tmp_path / "out"), "--no-plot",
            "--no-progress"]  # fmt: skip
    assert main(argv) == 1
    err = capsys.readouterr().err
    assert "error:" in err and "--trust-policy" in err and "internal error" not in err
    assert not marker.exists()
    # --trust-policy loads it (the payload runs: that is what the opt-in means)
    assert main([*argv, "--trust-policy"]) == 1
    assert marker.exists() and "internal error" not in capsys.readouterr().err


def test_campaign_policy_cells_refuse_a_crafted_model_and_check_its_digest(tmp_path):
    pytest.importorskip("pyarrow")
    from ship_gym.analysis import campaign as cp
    from ship_gym.analysis.policy_cells import read_policy_controller

    marker = tmp_path / "marker"
    run = _crafted_model(tmp_path / "run", marker, env_id="ship_gym/CapsizeAvoidance-v2")
    spec_file = tmp_path / "c.toml"
    spec_file.write_text(
        f"""
name = "trust"
ships = ["s175"]
loadings = [{{kg = 9.8}}]
headings_deg = [180]
froude_numbers = [0.3]
seeds = 1
duration_s = 5.0
dt_s = 0.1
controller = "policy:{run}"

[[seas]]
kind = "regular"
height_m = 4.0
wavelength_m = 200.0
ramp_s = 1.0
""",
        encoding="utf-8",
    )
    spec = cp.read_campaign(spec_file)
    assert spec.policy is not None
    assert spec.policy.model_sha256 == hashlib.sha256((run / "model.zip").read_bytes()).hexdigest()
    for executor in ("serial", "processes"):
        with pytest.raises(cp.CampaignError, match=r"refusing to load .*--trust-policy"):
            cp.run_campaign(spec, tmp_path / "store", executor=executor, progress=False)
    assert not marker.exists()
    # a worker loads only the file the driver checked: another file there is refused unread
    from ship_gym.analysis.policy_cells import run_policy_cells

    controller = read_policy_controller(run, field="controller")
    swapped = type(controller)(**{**controller.__dict__, "model_sha256": "0" * 64})
    with pytest.raises(UntrustedPolicyError, match="differs from the digest"):
        run_policy_cells(
            swapped, ship="s175", loading={}, sea=spec.seas[0], heading_deg=180.0,
            speed_mps=5.0, seeds=[0], duration_s=1.0, dt_s=0.1, integrator="holloway",
            capsize_angle_deg=60.0, trusted=True,
        )  # fmt: skip
    assert not marker.exists()


def test_every_shipped_policy_is_trusted_by_digest_and_ships_no_pickle():
    digests = shipped_policy_digests()
    models = sorted(SHIPPED.glob("*/*/model.zip"))
    assert models
    for model in models:
        digest = hashlib.sha256(model.read_bytes()).hexdigest()
        assert digests.get(digest) == f"{model.parent.parent.name}/{model.parent.name}", (
            f"{model} changed: update ship_gym/data/shipped_policies.json"
        )
        assert is_trusted_digest(digest)
        assert not list(model.parent.glob("*.pkl")), model.parent
    assert not is_trusted_digest("0" * 64) and not is_trusted_digest("not a digest")
    with pytest.raises(UntrustedPolicyError):
        check_policy_trust(b"anything", "x.zip")
    assert check_policy_trust(b"anything", "x.zip", trusted=True)


def test_the_npz_statistics_match_sb3_and_damaged_files_are_named(tmp_path):
    from stable_baselines3.common.running_mean_std import RunningMeanStd

    class _Norm:  # the attributes of a VecNormalize that are saved
        obs_rms = RunningMeanStd(shape=(3,))
        clip_obs, epsilon, norm_obs = 5.0, 1e-8, True

    rng = np.random.default_rng(1)
    _Norm.obs_rms.update(rng.normal(2.0, 3.0, size=(50, 3)))
    path = tmp_path / "vecnormalize.npz"
    save_obs_normalizer(_Norm, path)
    norm = read_obs_normalizer(path, (3,))
    obs = rng.normal(0.0, 20.0, size=(4, 3)).astype(np.float32)
    rms = _Norm.obs_rms
    expected = np.clip((obs - rms.mean) / np.sqrt(rms.var + 1e-8), -5.0, 5.0).astype(np.float32)
    assert np.array_equal(norm.normalize_obs(obs), expected)
    with pytest.raises(ValueError, match=r"vecnormalize\.npz: statistics of shape \(3,\), the mo"):
        read_obs_normalizer(path, (4,))
    bad = tmp_path / "bad" / "vecnormalize.npz"
    bad.parent.mkdir()
    for content in (b"random bytes \x00\x01", path.read_bytes()[:100]):
        bad.write_bytes(content)
        with pytest.raises(ValueError, match=r"bad/vecnormalize\.npz: not observation statistics"):
            read_obs_normalizer(bad)
    np.savez(bad, mean=np.zeros(3), var=-np.ones(3), count=1.0, clip_obs=1.0, epsilon=0.0,
             norm_obs=True)  # fmt: skip
    with pytest.raises(ValueError, match="negative variance"):
        read_obs_normalizer(bad)
    np.savez(bad, mean=np.array([object()], dtype=object))
    with pytest.raises(ValueError, match="not observation statistics"):
        read_obs_normalizer(bad)


@pytest.mark.parametrize(
    ("damage", "expected"),
    [
        ("random", r"vecnormalize\.npz: not observation statistics saved by ship-gym train"),
        ("truncated", r"vecnormalize\.npz: not observation statistics saved by ship-gym train"),
        ("shape", r"vecnormalize\.npz: statistics of shape \(3,\), the model observes shape"),
    ],
)
def test_evaluate_names_a_damaged_vecnormalize_file(tmp_path, capsys, damage, expected):
    run = tmp_path / "run"
    shutil.copytree(ROLL, run)
    stats = run / "vecnormalize.npz"
    if damage == "random":
        stats.write_bytes(np.random.default_rng(0).bytes(300))
    elif damage == "truncated":
        stats.write_bytes(stats.read_bytes()[:200])
    else:
        np.savez(stats, mean=np.zeros(3), var=np.ones(3), count=1.0, clip_obs=10.0,
                 epsilon=1e-8, norm_obs=True)  # fmt: skip
    argv = ["evaluate", "--env", "ship_gym/RollStabilization-v2", "--policies", f"model:{run}",
            "--episodes", "1", "--max-steps", "2", "--out", str(tmp_path / "out"), "--no-plot",
            "--no-progress"]  # fmt: skip
    assert main(argv) == 1
    err = capsys.readouterr().err
    assert "internal error" not in err
    import re

    assert re.search(expected, err), err
