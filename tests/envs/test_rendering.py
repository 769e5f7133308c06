"""Pictures of ship_gym.envs.rendering: size, type, determinism, and that they show the motion."""

import math
import warnings

import matplotlib
import numpy as np
import pytest

from ship_gym.envs.rendering import HumanViewer, RenderSnapshot, render_rgb

L, B, T, D = 175.0, 25.4, 9.5, 15.4  # S175 main dimensions [m]


def _snapshot(roll_deg: float = 0.0, time: float = 20.0, **changes) -> RenderSnapshot:
    x = np.linspace(-0.6 * L, 0.6 * L, 60)
    y = np.linspace(-B, B, 30)
    k = 2.0 * np.pi / 150.0
    t_hist = np.linspace(time - 20.0, time, 50)
    fields = {
        "time": time,
        "eta": np.array([0.0, 0.0, -0.3, math.radians(roll_deg), math.radians(1.5), 0.2]),
        "length": L,
        "beam": B,
        "draught": T,
        "depth": D,
        "profile_x": x,
        "profile_elevation": 2.0 * np.cos(k * x - 0.6 * time),
        "section_y": y,
        "section_elevation": np.full_like(y, 2.0 * np.cos(0.6 * time)),
        "history_time": t_hist,
        "history": {"roll [deg]": 10.0 * np.sin(0.4 * t_hist), "pitch [deg]": np.sin(t_hist)},
        "actions": {"fin angle [deg]": 12.5},
        "title": "test",
        "roll_limit": math.radians(40.0),
    }
    fields.update(changes)
    return RenderSnapshot(**fields)


def test_shape_and_dtype():
    frame = render_rgb(_snapshot(), width=320, height=240)
    assert frame.shape == (240, 320, 3)
    assert frame.dtype == np.uint8
    # not a blank picture: the hull grey, the sea blue and the white background all appear
    assert frame.std() > 20.0


def test_same_snapshot_same_pixels_even_after_other_frames():
    """Figures are reused between frames; nothing of a previous frame may leak into the next."""
    a = _snapshot(roll_deg=5.0)
    first = render_rgb(a)
    render_rgb(_snapshot(roll_deg=-30.0, time=200.0, eta=np.array([0, 0, 3.0, -0.5, 0.1, 1.0])))
    render_rgb(_snapshot(roll_deg=10.0, history={"x [m]": np.zeros(50)}))  # other layout
    np.testing.assert_array_equal(render_rgb(a), first)


def test_picture_changes_with_roll_in_the_section_panel():
    """φ = 0 vs φ = 30°: many pixels change, and they are in the section panel (right third).

    The roll angle moves the hull section by metres on a ~50 m wide panel, i.e. tens of pixels
    over the hull outline: thousands of pixels, far above the ~few hundred of the changed
    'roll +30.0°' text. The side profile (left two thirds) draws the y = 0 cut, which roll does not
    move, so it must stay identical apart from nothing (the history is the same).
    """
    upright = render_rgb(_snapshot(roll_deg=0.0)).astype(int)
    rolled = render_rgb(_snapshot(roll_deg=30.0)).astype(int)
    changed = np.any(upright != rolled, axis=2)
    top_half = changed[: changed.shape[0] // 2]
    section_part = top_half[:, int(0.68 * changed.shape[1]) :]
    profile_part = top_half[:, : int(0.6 * changed.shape[1])]
    assert section_part.sum() > 2000
    assert profile_part.sum() == 0


def test_snapshot_validation():
    with pytest.raises(ValueError, match="eta"):
        _snapshot(eta=np.zeros(5))
    with pytest.raises(ValueError, match="depth"):
        _snapshot(depth=5.0)
    with pytest.raises(ValueError, match="history"):
        _snapshot(history={"roll [deg]": np.zeros(3)})
    with pytest.raises(ValueError, match="width"):
        render_rgb(_snapshot(), width=10)


def test_diverged_state_still_draws():
    """A NaN pose (diverged simulation) must not raise when rendering the last frame."""
    frame = render_rgb(_snapshot(eta=np.full(6, np.nan)))
    assert frame.shape == (480, 640, 3)


def test_human_viewer_on_headless_backend_warns_once_and_keeps_frame():
    matplotlib.use("Agg")  # headless, as on the test machines (all tests here draw with Agg)
    viewer = HumanViewer(width=200, height=150)
    with pytest.warns(RuntimeWarning, match="headless"):
        viewer.show(_snapshot())
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        viewer.show(_snapshot(roll_deg=3.0))  # no second warning
    assert viewer.headless
    assert viewer.last_frame is not None
    assert viewer.last_frame.shape == (150, 200, 3)
    viewer.close()


def test_smoke_render_a_real_env_episode():
    """RollOneDOF-v0 (H2a) builds snapshots that this module draws, frame after frame."""
    import gymnasium

    pytest.importorskip("ship_gym.envs.roll_one_dof")
    env = gymnasium.make("ship_gym:ship_gym/RollOneDOF-v0", render_mode="rgb_array")
    env.reset(seed=0)
    frames = []
    for _ in range(3):
        env.step(np.array([0.5], np.float32))
        frames.append(env.render())
    assert all(f.shape == (480, 640, 3) and f.dtype == np.uint8 for f in frames)
    assert not np.array_equal(frames[0], frames[-1])  # the ship moved, the history grew
