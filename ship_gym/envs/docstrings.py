"""The environments' docstrings, composed from shared pieces written once: the observation table
of the common entries, the keyword table rows and the registered time limit.
"""

from __future__ import annotations

import inspect
import re
from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Any, TypeVar

from ship_gym.envs.registration import max_episode_steps

if TYPE_CHECKING:
    from ship_gym.envs.base import BatchedTask, TaskEnv


# =============================================================================================
# the environments' docstrings: shared pieces, written once
# =============================================================================================
SHIP_OBSERVATION_TABLE = """\
| # | name | unit | bound |
|---|---|---|---|
| 0 | roll φ | rad | ±π |
| 1 | pitch θ | rad | ±π/2 |
| 2 | heave (from the calm-water equilibrium, down positive) | m | ±30 |
| 3–5 | roll rate p, pitch rate q, heave velocity w (body) | rad/s, rad/s, m/s | 5, 5, 30 |
| 6 | yaw rate r | rad/s | ±2 |
| 7–8 | surge speed u, sway velocity v | m/s | ±30 |
| 9 | heading error wrap(ψ_ref − ψ) | rad | ±π |
| 10–11 | cos β, sin β of the mean relative wave heading β = χ − ψ | - | ±1 |
| 12 | rudder angle (servo) | rad | ±π/2 |
| 13 | shaft speed | rev/s | ±20 |"""
"""Markdown rows of the common observation entries 0–13 of every S175 task (the names and
bounds of ``_BASE_OBSERVATIONS``, the rudder angle and the shaft speed)."""

SHIP_ARGUMENTS: dict[str, tuple[str, str]] = {
    # name: (unit, meaning); an environment may give its own meaning for any of them
    "ship": ("-", "bundled ship name or ship file (.toml; ship-gym ship check FILE)"),
    "froude_number": ("-", "reference speed U = Fn √(g L) (radiation, diffraction, propeller)"),
    "speed_range_mps": ("m/s", "initial speed range (self-propulsion rpm); keep near U"),
    "hs_range_m": ("m", "significant wave height range"),
    "tp_range_s": ("s", "peak period range"),
    "wave_heading_range_deg": ("deg", "relative wave heading β (0 following, 180 head seas)"),
    "n_wave_components": ("-", "components of the irregular sea"),
    "wave_spreading_s": ("-", "cos-2s spreading exponent (None: long-crested)"),
    "wave_ramp_time_s": ("s", "start-up ramp of the waves (Matusiak 2003, eq. 12)"),
    "gm_range_m": ("m", "GM range of the loading (per episode; None: nominal)"),
    "kg_m": ("m", "KG of the nominal loading (None: the ship's; S175 9.55 m)"),
    "passenger_point_m": ("m", "body-frame passenger position (z down; None: scaled S175 point)"),
    "physics_dt_s": ("s", "physics time step"),
    "control_dt_s": ("s", "control step (integer multiple of physics_dt_s)"),
    "integrator": ("-", '"holloway" (1 force evaluation/step) or "rk4" (4)'),
    "hull_mesh": ("-", "offsets-hull mesh (sections, panels below/above water, deck)"),
    "precision": ("-", '"float32" or "float64" wave sums of the Froude–Krylov kernel'),
    "wind_speed_mps": ("m/s", "constant mean wind speed on the ship's windage (0: none)"),
    "wind_from_deg": ("deg", "earth direction the wind blows from (0: north, ahead at the start)"),
    "forward_speed_model": (
        "-",
        '"relative_motion" (speed terms on the motion relative to the waves) or '
        '"radiation_only" (the -v2 model)',
    ),
    "num_threads": ("-", "numba threads over the batch's ships (1: serial)"),
    "capsize_angle_deg": ("deg", "capsize roll angle (None: vanishing angle of the loading)"),
    "dangerous_roll_deg": ("deg", "roll angle of the Safe-RL cost"),
    "heading_weight": ("-", "weight of the heading term"),
    "heading_scale_deg": ("deg", "heading error scale"),
    "roll_weight": ("-", "weight of the roll term"),
    "roll_scale_deg": ("deg", "roll scale"),
    "effort_weight": ("-", "weight of the actuator effort term"),
    "capsize_penalty": ("-", "penalty paid at capsize"),
    "comfort_time_constant_s": ("s", "time constant of the running acceleration RMS"),
    "sensor_noise": ("-", "multiplier of the sensor accuracies (SENSOR_NOISE_STD)"),
    "wave_preview_m": ("m", "elevation preview: distances ahead of O, or (x, y) body-frame points"),
}
"""Unit and meaning of the keyword arguments shared by the ship environments (the rows of the
``## Arguments`` tables; :func:`env_docstring` takes each default from the task's signature)."""


RESET_OPTION_ROWS: dict[str, tuple[str, str]] = {
    # key: (unit, meaning and accepted values); the same names as the reset info, so that
    # reset(seed=s, options={k: info[k] ...}) replays an episode
    "wave_height_m": (
        "m",
        "wave height H (regular) or Hs (irregular), 0 … 30, not steeper than the breaking "
        "limit H/λ ≤ 1/7 (regular) or DNV-RP-C205's Hs/λp ≤ 1/15 … 1/25 (irregular)",
    ),
    "wave_period_s": ("s", "wave period T (regular) or peak period Tp (irregular), 1 … 40"),
    "wave_heading_deg": ("deg", "relative wave heading β (0 following, 180 head seas), −360 … 720"),
    "initial_speed_mps": ("m/s", "initial surge speed (self-propulsion shaft speed), 0.1 … 30"),
    "gm_m": ("m", "GM of the episode's loading, 0.05 … 10 (G moved, capsize angle follows)"),
    "roll_deg": ("deg", "initial roll angle, inside the capsize angle of the loading"),
    "roll_rate_dps": ("deg/s", "initial roll rate, −30 … 30"),
    "heading_setpoint_deg": ("deg", "initial heading set-point (instead of the drawn error)"),
}
"""Unit and meaning of the ``reset(options=...)`` keys of the ship environments."""


def reset_options_table(task_class: type[BatchedTask]) -> str:
    """The reset-options paragraph and table of a ship task (closing its Starting State
    section): every key it accepts, its unit and range."""
    keys = tuple(getattr(task_class, "RESET_OPTIONS", ())) + tuple(
        getattr(task_class, "task_reset_options", ())
    )
    lines = [
        "``reset(options=dict(...))`` fixes what the episode's generator would draw (the draws "
        "still "
        "happen, so the rest of the episode is that of the same seed); the sea, speed, GM and "
        "set-point keys are those of the reset info, so an episode replays from its seed and "
        "info. Unknown keys, a non-mapping "
        "and values outside the ranges raise (ValueError/TypeError naming the key). The vector "
        "env applies them to every episode being reset (``reset_mask`` selects them); "
        "autoresets draw afresh.",
        "",
        "| key | unit | meaning and accepted values |",
        "|---|---|---|",
    ]
    for key in keys:
        unit, meaning = RESET_OPTION_ROWS[key]
        lines.append(f"| {key} | {unit} | {meaning} |")
    return "\n".join(lines)


def _format_default(value: Any) -> str:
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, float):
        return f"{value:g}" if value != 0.0 else "0"
    if isinstance(value, tuple):
        return "(" + ", ".join(_format_default(v) for v in value) + ")"
    return repr(value)


def _task_parameters(task_class: type[BatchedTask]) -> list[inspect.Parameter]:
    """The keyword arguments of ``task_class.__init__`` after ``num_envs``."""
    params = list(inspect.signature(task_class.__init__).parameters.values())
    return [p for p in params[1:] if p.name != "num_envs"]


def arguments_table(task_class: type[BatchedTask], rows: Mapping[str, tuple[str, str]]) -> str:
    """The ``## Arguments`` markdown table of a task: every keyword argument of its
    ``__init__`` in signature order, its default, and (unit, meaning) from ``rows`` or else
    :data:`SHIP_ARGUMENTS`.

    Raises
    ------
    ValueError
        A keyword argument without a documented unit and meaning.
    """
    known = {**SHIP_ARGUMENTS, **rows}
    lines = ["| kwarg | default | unit | meaning |", "|---|---|---|---|"]
    for p in _task_parameters(task_class):
        if p.name not in known:
            raise ValueError(f"{task_class.__name__} keyword {p.name!r} has no documented unit")
        unit, meaning = known[p.name]
        lines.append(f"| {p.name} | {_format_default(p.default)} | {unit} | {meaning} |")
    return "\n".join(lines)


def _time_limit(name: str, task_class: type[BatchedTask]) -> str:
    steps = max_episode_steps(name)
    defaults = {p.name: p.default for p in _task_parameters(task_class)}
    dt = defaults.get("control_dt_s", defaults.get("control_dt"))
    if dt is None:
        raise ValueError(f"{task_class.__name__} has no control_dt default for {{time_limit}}")
    return f"``MAX_EPISODE_STEPS`` = {steps} control steps = {steps * dt:g} s at the default step"


def _fill(doc: str, marker: str, text: str) -> str:
    """Replace ``{marker}`` in ``doc``, indenting the lines of ``text`` like the marker."""
    found = re.search(rf"^([ \t]*)(.*?)\{{{marker}\}}", doc, re.MULTILINE)
    if found is None:
        raise ValueError(f"docstring has no {{{marker}}} marker")
    indent = found.group(1)
    return doc.replace(f"{{{marker}}}", text.replace("\n", "\n" + indent), 1)


_EnvType = TypeVar("_EnvType", bound="type[TaskEnv]")


VERSION_HISTORY: tuple[str, ...] = (
    "v0: initial version.",
    "v1: one compiled engine call per control step; servos sampled at each physics step "
    "and advanced by the exact solution of their lag and rate limit (v0 integrated them as "
    "ODE states: under Holloway's scheme a constant command cycled); float32 wave sums by "
    "default (docs/accuracy/results.md: ≤ 3e-5 % on every motion statistic).",
)
"""The version history every ship environment shares (an env appends its own lines)."""

FORWARD_SPEED_V3 = (
    "v3: forward speed in every heading (issue #34): the diffraction force at speed in "
    "relative-motion form with the scattered flow's Kirchhoff moment, and the moment "
    "high-passed below ω_c = 0.25 √(g/L) (ship_gym.hydro.forward_speed), so that the speed "
    "terms act on the motion relative to the incident flow (v2's radiated momentum alone "
    "pitched the S175 0.45 k a in beam seas at Fn 0.3 and made capsizes in beam and "
    "quartering seas that strip theory does not have). The -v2 id stays registered with "
    'forward_speed_model="radiation_only", the model its published results were made with.'
)
"""The v3 line every ship environment appends to its version history."""


def env_docstring(
    arguments: Mapping[str, tuple[str, str]] | None = None,
    version_history: Sequence[str] = VERSION_HISTORY,
) -> Callable[[_EnvType], _EnvType]:
    """Class decorator completing a ship environment's Gymnasium v5 docstring.

    The class docstring holds the sections Description … Episode End; this fills the markers
    ``{ship_observations}`` (:data:`SHIP_OBSERVATION_TABLE`) and ``{time_limit}`` (the
    registered ``MAX_EPISODE_STEPS`` of ``<Name>Env`` and its duration at the default control
    step) where it has them, and appends ``## Arguments`` (:func:`arguments_table` of the
    class's ``task_class``, with the environment's own ``arguments`` rows, name → (unit,
    meaning)) and ``## Version History``.
    """

    def decorate(cls: _EnvType) -> _EnvType:
        task_class = cls.task_class
        name = cls.__name__.removesuffix("Env")
        doc = (cls.__doc__ or "").rstrip()
        if "{ship_observations}" in doc:
            doc = _fill(doc, "ship_observations", SHIP_OBSERVATION_TABLE)
        if "{time_limit}" in doc:
            doc = _fill(doc, "time_limit", _time_limit(name, task_class))
        # the reset options close the Starting State section (the v5 sections stay as they are)
        found = re.search(r"^([ \t]*)## Episode End", doc, re.MULTILINE)
        if found is not None:
            indent = found.group(1)
            text = "**Reset options.** " + reset_options_table(task_class)
            doc = (
                doc[: found.start()]
                + text.replace("\n", "\n" + indent).replace("\n" + indent + "\n", "\n\n")
                + "\n\n"
                + doc[found.start() :]
            )
            doc = doc[: found.start()] + indent + doc[found.start() :]
        sections = [
            "## Arguments",
            arguments_table(task_class, arguments or {}),
            "## Version History",
            "\n".join(f"* {line}" for line in version_history),
        ]
        cls.__doc__ = doc + "".join(_indent(f"\n\n{part}") for part in sections) + "\n    "
        return cls

    return decorate


def _indent(text: str, indent: str = "    ") -> str:
    """Indent the lines of a docstring fragment like a class docstring's body."""
    return "\n".join(indent + line if line else line for line in text.split("\n"))


def vector_env_docstring(env_class: type) -> str:
    """The docstring of the vector face of ``env_class`` (N episodes, seeds s + i)."""
    return (
        f"N episodes of :class:`{env_class.__name__}` in one BatchSimulator (same keyword "
        "arguments).\n\n"
        "    Episode i reset with ``seed=s`` is the single environment reset with "
        "``seed=s + i``.\n    "
    )
