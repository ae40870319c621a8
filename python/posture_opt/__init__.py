"""posture_opt: fatigue-aware posture planning for manual work, from Python.

The Rust library ``posture-opt`` (the Ma et al. 2009 dynamic muscle fatigue model, a whole-body
worker, a sequential-QP posture planner) behind a small Python API that mirrors the command line:

* :func:`load_task` -- a task from a file, a dict or YAML text (:class:`Task`);
* :func:`plan` -- ``posture-opt plan --json``: the plan and its assessment;
* :func:`compare` / :func:`merge_compare` -- ``posture-opt compare``: layouts ranked, whole or in
  shards that merge into the result of one run;
* :func:`sweep` / :func:`merge_sweep` -- ``posture-opt sweep``: one task for a population;
* :func:`evaluate` (arrays), :func:`evaluate_file` (CSV / OpenSim) and :class:`Evaluator` (one
  sample at a time, for capture loops) -- ``posture-opt evaluate``;
* :func:`statics` -- ``posture-opt statics``: holding torques of a body at a posture.

Results are the command line's ``--json`` documents as dicts, with the same key names; the big
columns are numpy arrays (each function says which). Bad input raises :class:`Error` (a
``ValueError``) with the command line's message; a failure of the optimiser raises
:class:`PlanningError` (a ``RuntimeError``). Planning, studies and evaluation release the GIL, so
threads run them in parallel; planning is deterministic.

Units are SI (m, rad, N, N·m, s) except the fatigue index U and the rates, which are per minute
(``fatigue_u_min``, ``k_per_min``). Capacity is a fraction of the rested strength (MVC).
"""

from __future__ import annotations

import difflib
import json
import os
from typing import Any, Dict, Iterable, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _posture_opt as _native
from ._posture_opt import (
    DEFAULT_CAPACITY_FLOOR,
    HOLD_RULE,
    RANKING_RULE,
    Error,
    PlanningError,
    Task,
)

__version__: str = _native.__version__

__all__ = [
    "DEFAULT_CAPACITY_FLOOR",
    "HOLD_RULE",
    "RANKING_RULE",
    "Error",
    "Evaluator",
    "PlanningError",
    "Task",
    "compare",
    "default_setup",
    "evaluate",
    "evaluate_file",
    "jsonable",
    "load_task",
    "merge_compare",
    "merge_sweep",
    "plan",
    "statics",
    "sweep",
    "task_schema",
]

PathLike = Union[str, "os.PathLike[str]"]
#: What the functions accept as a task: a :class:`Task`, a path to a task file, YAML text (a
#: string with a line break or starting with ``{``) or a dict shaped like a task file.
TaskLike = Union[Task, PathLike, Mapping[str, Any]]
#: A shard: ``(i, n)`` with ``0 <= i < n`` (0-based, for ``range(n)``), or the command line's
#: ``"i/n"`` with ``1 <= i <= n``. Item ``j`` of a study belongs to shard ``j mod n``.
ShardLike = Union[Tuple[int, int], str]

# ---------------------------------------------------------------------------------------------
# Tasks


def _is_yaml_text(s: str) -> bool:
    t = s.lstrip()
    return "\n" in s or t.startswith("{")


def load_task(source: TaskLike, *, path: Optional[PathLike] = None) -> Task:
    """Loads and validates a task.

    ``source`` is a :class:`Task` (returned as is), a path to a task file (YAML), YAML (or JSON)
    text -- a string with a line break, or starting with ``{`` -- or a dict shaped like a task
    file (``posture-opt schema`` / :func:`task_schema`).

    ``path`` names text or a dict in messages and locates a relative ``robot:`` (default
    ``"<string>"`` / ``"<dict>"`` in the current directory). Raises :class:`Error` with the
    command line's message (file, field, line).
    """
    if isinstance(source, Task):
        return source
    if isinstance(source, Mapping):
        try:
            text = json.dumps(source, indent=1, allow_nan=False)
        except (TypeError, ValueError) as e:
            raise Error(f"{path or '<dict>'}: not a task file's data: {e}") from None
        return _native.task_from_yaml(text, os.fspath(path) if path is not None else "<dict>")
    if isinstance(source, str) and _is_yaml_text(source):
        return _native.task_from_yaml(source, os.fspath(path) if path is not None else "<string>")
    if isinstance(source, (str, os.PathLike)):
        if path is not None:
            raise Error("path= names text or a dict; a file is named by itself")
        return _native.task_from_file(os.fspath(source))
    raise TypeError(f"a task is a Task, a path, YAML text or a dict, not {type(source).__name__}")


def default_setup(
    sex: str = "male",
    stature_m: float = 1.755,
    mass_kg: float = 78.0,
    strength_percentile: float = 50.0,
    parameters: Optional[str] = None,
) -> Task:
    """The set-up of an evaluation without a task file: the generated whole-body worker.

    The defaults are the command line's (``evaluate`` without ``--task``); ``parameters`` names a
    fatigue parameter set (``data/fatigue_sets.yaml``). The task's phases are a placeholder: use
    it for :func:`evaluate`, :class:`Evaluator` and :func:`statics`, not for planning studies.
    """
    return _native.default_setup(sex, float(stature_m), float(mass_kg), float(strength_percentile), parameters)


def task_schema() -> Dict[str, Any]:
    """The JSON Schema of task files (``posture-opt schema``)."""
    return json.loads(_native.task_schema())


# ---------------------------------------------------------------------------------------------
# Conversions


def _array(v: Any) -> np.ndarray:
    # null in the JSON (a NaN in the Rust result) becomes NaN
    return np.asarray(v, dtype=np.float64)


def _matrix(v: Any, columns: int) -> np.ndarray:
    return _array(v).reshape(len(v), columns)


def _plan_arrays(doc: Dict[str, Any]) -> Dict[str, Any]:
    steps = doc.get("steps")
    nh = len(doc.get("half_joint_ids") or [])
    if isinstance(steps, dict):
        for k in ("t_s", "duration_s"):
            if k in steps:
                steps[k] = _array(steps[k])
        for k in ("cycle", "posture"):
            if k in steps:
                steps[k] = np.asarray(steps[k], dtype=np.int64)
        for k in ("capacity", "fatigue_u_min"):
            if k in steps:
                steps[k] = _matrix(steps[k], nh)
    for p in doc.get("postures") or []:
        for k in ("q_rad", "torque_nm", "load", "mvc_nm"):
            if k in p:
                p[k] = _array(p[k])
    summary = doc.get("summary")
    if isinstance(summary, dict) and "final_capacity" in summary:
        summary["final_capacity"] = _array(summary["final_capacity"])
    return doc


def _evaluation_arrays(doc: Dict[str, Any], nh: int) -> Dict[str, Any]:
    for k in ("final_capacity", "final_fatigue_u_min"):
        doc[k] = _array(doc[k])
    tl = doc.get("timeline")
    if isinstance(tl, dict):
        tl["t_s"] = _array(tl["t_s"])
        for k in ("capacity", "fatigue_u_min", "load"):
            tl[k] = _matrix(tl[k], nh)
    return doc


def _from_bytes(b: bytes, shape: Tuple[int, ...]) -> np.ndarray:
    return np.frombuffer(b, dtype="<f8").astype(np.float64).reshape(shape)


def _f64_bytes(a: np.ndarray) -> bytes:
    return np.ascontiguousarray(a, dtype="<f8").tobytes()


def jsonable(obj: Any) -> Any:
    """A result with its numpy arrays turned back into lists (for ``json.dumps``)."""
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, Mapping):
        return {k: jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [jsonable(v) for v in obj]
    return obj


def _shard(shard: Optional[ShardLike]) -> Optional[str]:
    if shard is None:
        return None
    if isinstance(shard, str):
        return shard  # the command line's "i/n", checked by the library
    try:
        i, n = shard
        i, n = int(i), int(n)
    except (TypeError, ValueError):
        raise Error(f"shard: give (i, n) with 0 <= i < n <= 10000, or 'i/n' with 1 <= i <= n, got {shard!r}") from None
    if not (0 <= i < n <= 10_000):
        raise Error(f"shard: (i, n) needs 0 <= i < n <= 10000 (i counts from 0), got ({i}, {n})")
    return f"{i + 1}/{n}"


def _threads(threads: Optional[int]) -> Optional[int]:
    if threads is None:
        return None
    if isinstance(threads, bool) or not isinstance(threads, int) or threads < 1:
        raise Error(f"threads must be a whole number of at least 1, got {threads!r}")
    return threads


def _floor(capacity_floor: float) -> float:
    try:
        return float(capacity_floor)
    except (TypeError, ValueError):
        raise Error(f"capacity_floor: must be a number between 0 and 1, got '{capacity_floor}'") from None


# ---------------------------------------------------------------------------------------------
# Planning and studies


def plan(
    task: TaskLike,
    *,
    adapt: bool = True,
    fatigue_only: bool = False,
    capacity_floor: float = DEFAULT_CAPACITY_FLOOR,
    zones: bool = True,
    gaze: bool = True,
) -> Dict[str, Any]:
    """Plans postures for a task and assesses the plan: ``posture-opt plan --json``.

    ``adapt=False`` plans once and holds the postures (``--no-adapt``); ``fatigue_only`` drops the
    discomfort term, the step cost and the asymmetry cost (the posture zones stay); ``zones=False``
    leaves the postures free of the acceptable zones (``--no-zones``); ``gaze=False`` leaves every
    phase's head free instead of looking at its work (``--no-gaze``); ``capacity_floor`` is the
    work/rest advice's floor (0 < floor < 1).

    Returns the document's dict (``task``, ``joints``, ``half_joint_ids``, ``half_joints``,
    ``postures``, ``steps``, ``summary``, ``assessment``, ...). numpy arrays: ``steps["t_s"]``,
    ``steps["duration_s"]`` (n), ``steps["cycle"]``, ``steps["posture"]`` (n, int),
    ``steps["capacity"]``, ``steps["fatigue_u_min"]`` (n x half-joints, ordered like
    ``half_joint_ids``), each posture's ``q_rad``, ``torque_nm``, ``load``, ``mvc_nm`` and
    ``summary["final_capacity"]``.
    """
    t = load_task(task)
    doc = json.loads(_native.plan(t, bool(adapt), bool(fatigue_only), _floor(capacity_floor), bool(zones), bool(gaze)))
    return _plan_arrays(doc)


def _names_of(sources: Sequence[TaskLike], tasks: Sequence[Task], names: Optional[Sequence[str]]) -> List[str]:
    if names is not None:
        names = [str(n) for n in names]
        if len(names) != len(tasks):
            raise Error(f"{len(names)} names for {len(tasks)} layouts")
        return names
    out = []
    for s, t in zip(sources, tasks):
        out.append(os.fspath(s) if isinstance(s, (str, os.PathLike)) and not (isinstance(s, str) and _is_yaml_text(s)) else t.path)
    return out


def compare(
    tasks: Sequence[TaskLike],
    *,
    names: Optional[Sequence[str]] = None,
    adapt: bool = True,
    fatigue_only: bool = False,
    capacity_floor: float = DEFAULT_CAPACITY_FLOOR,
    shard: Optional[ShardLike] = None,
    threads: Optional[int] = None,
) -> Dict[str, Any]:
    """Compares workstation layouts (one task each), ranked: ``posture-opt compare --json``.

    ``names`` name the layouts (``file`` in the result); by default a file's path as given, else
    the task's ``path``. With ``shard=(i, n)`` only the layouts ``j`` with ``j % n == i`` are
    planned and the result is a shard result (``kind``, ``shard``, ``outcomes``, ...) for
    :func:`merge_compare`; the shards of one study merge into exactly the unsharded result.
    ``threads`` limits the threads planning uses (default: all cores).

    Returns the comparison: ``layouts`` in rank order (each with ``rank``, ``index``, ``file``,
    ``feasible``, ``total_u_min``, ``minutes_to_exhaustion``, ...), ``robustness``,
    ``findings``, ``ranking_rule``.
    """
    if isinstance(tasks, (str, os.PathLike, Mapping, Task)):
        raise TypeError("compare takes a sequence of tasks (one per layout)")
    sources = list(tasks)
    loaded = [load_task(s) for s in sources]
    nm = _names_of(sources, loaded, names)
    return json.loads(
        _native.compare(loaded, nm, bool(adapt), bool(fatigue_only), _floor(capacity_floor), _shard(shard), _threads(threads))
    )


def _shard_texts(shards: Iterable[Any], names: Optional[Sequence[str]]) -> List[Tuple[str, str]]:
    out: List[Tuple[str, str]] = []
    shards = list(shards)
    if names is not None and len(list(names)) != len(shards):
        raise Error(f"{len(list(names))} names for {len(shards)} shard results")
    for k, s in enumerate(shards):
        if isinstance(s, Mapping):
            name = f"shard {s.get('shard', k + 1)}"
            text = json.dumps(jsonable(s))
        elif isinstance(s, str) and s.lstrip().startswith("{"):
            name, text = f"shard result {k + 1}", s
        elif isinstance(s, (str, os.PathLike)):
            name = os.fspath(s)
            try:
                with open(name, encoding="utf-8") as f:
                    text = f.read()
            except OSError as e:
                raise Error(f"{name}: cannot read: {e.strerror or e}") from None
        else:
            raise TypeError(f"a shard result is a dict, JSON text or a file, not {type(s).__name__}")
        out.append((str(names[k]) if names is not None else name, text))
    return out


def merge_compare(shards: Iterable[Any], *, names: Optional[Sequence[str]] = None) -> Dict[str, Any]:
    """Merges compare shard results into one comparison: ``posture-opt compare --merge --json``.

    Each shard result is a dict returned by ``compare(..., shard=...)``, its JSON text, or a file
    written by ``posture-opt compare --shard i/n --json``. ``names`` name them in messages.
    Raises :class:`Error` when they do not make one study (options differ, a layout is missing or
    twice).
    """
    return json.loads(_native.merge_compare(_shard_texts(shards, names)))


def sweep(
    task: TaskLike,
    *,
    sample: Optional[int] = None,
    seed: int = 1,
    adapt: bool = True,
    fatigue_only: bool = False,
    capacity_floor: float = DEFAULT_CAPACITY_FLOOR,
    shard: Optional[ShardLike] = None,
    threads: Optional[int] = None,
) -> Dict[str, Any]:
    """Plans one task for a population of workers: ``posture-opt sweep --json``.

    The population is the 5th/50th/95th-percentile women and men, or with ``sample=n`` n workers
    drawn with ``seed`` (sex alternating; stature, mass and strength percentile drawn). The task's
    ``robot`` is replaced by each worker's generated body. With ``shard=(i, n)`` only workers
    ``j % n == i`` are planned and the result is a shard result for :func:`merge_sweep`.

    Returns the sweep: ``workers`` (each with ``can_do``, ``problems``, ``total_u_min``,
    ``minutes_to_exhaustion``, ...), ``cannot_do``, ``sustain_all`` / ``sustain_women`` /
    ``sustain_men`` (share with a Wilson interval), ``note``.
    """
    t = load_task(task)
    if sample is not None:
        sample = int(sample)
        if sample < 1:
            raise Error("sample must be at least 1")
    return json.loads(
        _native.sweep(t, sample, int(seed), bool(adapt), bool(fatigue_only), _floor(capacity_floor), _shard(shard), _threads(threads))
    )


def merge_sweep(shards: Iterable[Any], *, names: Optional[Sequence[str]] = None) -> Dict[str, Any]:
    """Merges sweep shard results into one sweep: ``posture-opt sweep --merge --json``.

    Shard results as for :func:`merge_compare` (dicts from ``sweep(..., shard=...)``, JSON text or
    files written by ``posture-opt sweep --shard i/n --json``).
    """
    return json.loads(_native.merge_sweep(_shard_texts(shards, names)))


# ---------------------------------------------------------------------------------------------
# Evaluating recorded work


def _setup(task: Optional[TaskLike]) -> Task:
    return default_setup() if task is None else load_task(task)


def _q_matrix(t: Task, q: Any, n: Optional[int]) -> np.ndarray:
    """q as samples x joints (body order); a mapping gives columns by joint name (others 0)."""
    names = t.joint_names
    if isinstance(q, Mapping):
        cols: Dict[int, np.ndarray] = {}
        for name, col in q.items():
            if name not in names:
                hint = difflib.get_close_matches(str(name), names, n=1)
                raise Error(
                    f"q: '{name}' is not a moving joint of the body"
                    + (f" (did you mean '{hint[0]}'?)" if hint else "")
                )
            cols[names.index(name)] = np.asarray(col, dtype=np.float64).reshape(-1)
        m = n if n is not None else (len(next(iter(cols.values()))) if cols else 1)
        out = np.zeros((m, len(names)))
        for k, c in cols.items():
            if c.shape[0] != m:
                raise Error(f"q: '{names[k]}' has {c.shape[0]} values for {m} samples")
            out[:, k] = c
        return out
    a = np.asarray(q, dtype=np.float64)
    if n is None:  # one sample
        if a.ndim != 1 or a.shape[0] != len(names):
            raise Error(f"q: a sample needs {len(names)} joint angles (body order: Task.joint_names), got shape {a.shape}")
        return a.reshape(1, -1)
    if a.ndim == 1 and len(names) == 1:
        a = a.reshape(-1, 1)
    if a.ndim != 2 or a.shape != (n, len(names)):
        raise Error(f"q: expected shape ({n}, {len(names)}) (samples x joints, body order: Task.joint_names), got {a.shape}")
    return a


def _forces(force: Any, n: Optional[int]) -> Tuple[np.ndarray, Tuple[bool, bool]]:
    """Hand forces as samples x 2 x 3 and which hands they give."""
    m = 1 if n is None else n
    out = np.zeros((m, 2, 3))
    if force is None:
        return out, (False, False)
    if isinstance(force, Mapping):
        given = [False, False]
        for key, v in force.items():
            if key not in ("right", "left"):
                raise Error(f"force: the hands are 'right' and 'left', got '{key}'")
            h = 0 if key == "right" else 1
            a = np.asarray(v, dtype=np.float64)
            if a.shape not in ((m, 3),) + (((3,),) if n is None else ()):
                raise Error(f"force['{key}']: expected shape ({m}, 3), got {a.shape}")
            out[:, h, :] = a.reshape(m, 3)
            given[h] = True
        return out, (given[0], given[1])
    a = np.asarray(force, dtype=np.float64)
    single = n is None
    if a.shape == ((3,) if single else (m, 3)):
        out[:, 0, :] = a.reshape(m, 3)
        return out, (True, False)
    if a.shape == ((2, 3) if single else (m, 2, 3)):
        out[:, :, :] = a.reshape(m, 2, 3)
        return out, (True, True)
    want = "(3,) or (2, 3)" if single else f"({m}, 3) or ({m}, 2, 3)"
    raise Error(f"force: expected shape {want} (the force the environment applies on the hand, N), got {a.shape}")


def evaluate(
    t: Any,
    q: Any,
    force: Any = None,
    *,
    task: Optional[TaskLike] = None,
    degrees: bool = False,
    hand_load_kg: Tuple[float, float] = (0.0, 0.0),
) -> Dict[str, Any]:
    """Evaluates recorded work given as arrays into a fatigue timeline (``evaluate --json``).

    * ``t`` -- sample times [s], shape (n,), strictly increasing;
    * ``q`` -- joint angles, shape (n, nq) in the body's order (``Task.joint_names``), or a dict
      joint name -> (n,) column (joints not named stay at 0); radians, or degrees with
      ``degrees=True``;
    * ``force`` -- the force the environment applies on the hands [N], world frame: shape (n, 3)
      for the right hand, (n, 2, 3) for right and left, or a dict ``{"right": (n, 3), "left":
      (n, 3)}``. A hand without forces carries ``hand_load_kg`` (right, left) as a constant load;
    * ``task`` -- gives the body, worker, stance and fatigue parameters (its phases are not
      used); default :func:`default_setup`.

    The hold rule is the command line's (:data:`HOLD_RULE`): each sample's posture and loads hold
    until the next sample. Returns the ``evaluate --json`` document (``half_joint_ids``,
    ``final_capacity``, ``total_u_min``, ``exhaustions``, ``timeline``, ...; ``source`` is
    ``"arrays"``) with numpy arrays for ``final_capacity``, ``final_fatigue_u_min`` and the
    timeline's columns, plus ``per_sample``: ``t_s`` (n) and ``capacity``, ``fatigue_u_min``,
    ``load`` (n x half-joints), the state at each sample's time (before its own load acts) and
    its load. Raises :class:`Error` naming the sample (0-based) for a bad one.
    """
    tk = _setup(task)
    ta = np.asarray(t, dtype=np.float64).reshape(-1)
    n = ta.shape[0]
    qa = _q_matrix(tk, q, n)
    fa, given = _forces(force, n)
    doc_text, cap, u, load = _native.evaluate_arrays(
        tk, _f64_bytes(ta), _f64_bytes(qa), _f64_bytes(fa) if any(given) else b"", given, bool(degrees), _hand_loads(hand_load_kg)
    )
    nh = len(tk.half_joint_ids)
    doc = _evaluation_arrays(json.loads(doc_text), nh)
    doc["per_sample"] = {
        "t_s": ta.copy(),
        "capacity": _from_bytes(cap, (n, nh)),
        "fatigue_u_min": _from_bytes(u, (n, nh)),
        "load": _from_bytes(load, (n, nh)),
    }
    return doc


def _hand_loads(hand_load_kg: Any) -> Tuple[float, float]:
    try:
        r, l = hand_load_kg
        return float(r), float(l)
    except (TypeError, ValueError):
        raise Error(f"hand_load_kg: give (right, left) in kg, got {hand_load_kg!r}") from None


def evaluate_file(
    recording: PathLike,
    *,
    task: Optional[TaskLike] = None,
    mapping: Optional[PathLike] = None,
    degrees: bool = False,
    hand_load_kg: Tuple[float, float] = (0.0, 0.0),
) -> Dict[str, Any]:
    """Evaluates a recording file: ``posture-opt evaluate RECORDING --json``.

    CSV (``t_s``, joint columns, hand loads ``load_kg`` / ``force_x_n``... ), or OpenSim
    ``.mot``/``.sto`` with a ``mapping`` file. ``task`` as in :func:`evaluate`. The document's
    ``final_capacity``, ``final_fatigue_u_min`` and timeline columns are numpy arrays.
    """
    tk = _setup(task)
    doc = json.loads(
        _native.evaluate_file(
            tk,
            os.fspath(recording),
            os.fspath(mapping) if mapping is not None else None,
            bool(degrees),
            _hand_loads(hand_load_kg),
        )
    )
    return _evaluation_arrays(doc, len(tk.half_joint_ids))


class Evaluator:
    """Live evaluation: push samples one at a time as a capture loop delivers them.

    The same code as :func:`evaluate` (samples pushed one by one give exactly the arrays'
    result). ``task``, ``degrees`` and ``hand_load_kg`` as in :func:`evaluate`::

        ev = posture_opt.Evaluator(task)
        for t, q, f in capture():
            line = ev.push(t, q, f)          # capacity now, and any group that just gave out
            if line["exhausted"]: ...
        doc = ev.result()                    # the evaluate --json document so far
    """

    def __init__(
        self,
        task: Optional[TaskLike] = None,
        *,
        degrees: bool = False,
        hand_load_kg: Tuple[float, float] = (0.0, 0.0),
    ) -> None:
        self.task: Task = _setup(task)
        self._ev = _native._Evaluator(self.task, bool(degrees), _hand_loads(hand_load_kg), "stream")
        self._nh = len(self.task.half_joint_ids)
        #: Half-joint ids, the order of every per-half-joint array.
        self.half_joint_ids: List[str] = self.task.half_joint_ids
        #: The muscle groups in words, same order.
        self.groups: List[str] = self.task.groups

    def push(self, t: float, q: Any, force: Any = None) -> Dict[str, Any]:
        """Takes one sample: time [s], joint angles (nq, body order, or a dict name -> angle),
        and the hands' forces [N] ((3,) right, (2, 3) right and left, or a dict).

        Returns the ``evaluate --stream`` line: ``t_s``, ``capacity`` and ``fatigue_u_min``
        (arrays per half-joint: the state at this sample's time, before its own load acts) and
        ``exhausted`` (exhaustion events new with this sample). A refused sample raises
        :class:`Error` and leaves the state as it was.
        """
        qa = _q_matrix(self.task, q, None)[0]
        fa, given = _forces(force, None)
        new = self._ev.push(
            float(t),
            qa.tolist(),
            fa[0, 0].tolist() if given[0] else None,
            fa[0, 1].tolist() if given[1] else None,
        )
        return {
            "t_s": float(t),
            "capacity": self.capacity,
            "fatigue_u_min": self.fatigue_u_min,
            "exhausted": json.loads(self._ev.last_events(new)) if new else [],
        }

    def push_many(self, t: Any, q: Any, force: Any = None) -> int:
        """Takes many samples at once (arrays as :func:`evaluate`); returns the number of new
        exhaustion events. Stops at the first bad sample (raising :class:`Error`), keeping those
        before it."""
        ta = np.asarray(t, dtype=np.float64).reshape(-1)
        n = ta.shape[0]
        qa = _q_matrix(self.task, q, n)
        fa, given = _forces(force, n)
        return int(self._ev.push_many(_f64_bytes(ta), _f64_bytes(qa), _f64_bytes(fa) if any(given) else b"", given))

    @property
    def capacity(self) -> np.ndarray:
        """Capacity per half-joint now (fraction of MVC)."""
        return _from_bytes(self._ev.capacity(), (self._nh,))

    @property
    def fatigue_u_min(self) -> np.ndarray:
        """Fatigue index U [min] per half-joint now."""
        return _from_bytes(self._ev.fatigue_u_min(), (self._nh,))

    @property
    def load(self) -> np.ndarray:
        """Relative load per half-joint of the last sample (held until the next)."""
        return _from_bytes(self._ev.load(), (self._nh,))

    @property
    def exhaustions(self) -> List[Dict[str, Any]]:
        """Every exhaustion event so far."""
        return json.loads(self._ev.events())

    @property
    def samples(self) -> int:
        """Samples taken."""
        return int(self._ev.samples)

    @property
    def t_s(self) -> Optional[float]:
        """Time of the last sample."""
        return self._ev.t_s

    def result(self) -> Dict[str, Any]:
        """The ``evaluate --json`` document of the samples so far (``source`` ``"stream"``),
        with arrays as :func:`evaluate` (without ``per_sample``)."""
        return _evaluation_arrays(json.loads(self._ev.document()), self._nh)

    def __repr__(self) -> str:
        return f"<posture_opt.Evaluator: {self.samples} samples, task '{self.task.name}'>"


# ---------------------------------------------------------------------------------------------
# Statics


def _vec3(name: str, v: Any) -> Optional[List[float]]:
    if v is None:
        return None
    a = np.asarray(v, dtype=np.float64)
    if a.shape != (3,):
        raise Error(f"{name}: expected X, Y, Z, got shape {a.shape}")
    return a.tolist()


def statics(
    body: Union[TaskLike, PathLike],
    frame: Optional[str] = None,
    q: Any = None,
    *,
    hand_load_kg: Optional[float] = None,
    hand_force: Any = None,
    gravity: Any = None,
) -> Dict[str, Any]:
    """Joint positions, Jacobian and holding torques of a body at one posture:
    ``posture-opt statics --json``.

    * ``body`` -- a URDF file (``.urdf``), or a task (:class:`Task`, task file, dict or YAML) whose
      body is used (its right hand frame and gravity are then the defaults);
    * ``frame`` -- the link or joint whose frame origin is the hand point;
    * ``q`` -- a dict joint name -> rad (joints not named at 0) or an array of all joints in body
      order;
    * ``hand_load_kg`` -- a carried load (force = mass x gravity), or ``hand_force`` -- the force
      the environment applies on the hand [N], world frame;
    * ``gravity`` -- [m/s²], default (0, 0, -9.81).

    Returns the document (``frame``, ``position_m``, ``joints`` -- name, q_rad,
    gravity_torque_nm, load_torque_nm, torque_nm --, ``jacobian`` three rows x, y, z) with
    ``position_m`` as an array, plus arrays in joint order: ``joint_names``, ``q_rad``,
    ``gravity_torque_nm``, ``load_torque_nm``, ``torque_nm`` and ``jacobian_matrix`` (3 x n).
    """
    robot: Optional[str] = None
    task: Optional[Task] = None
    if isinstance(body, (str, os.PathLike)) and not (isinstance(body, str) and _is_yaml_text(body)) and os.fspath(body).lower().endswith(".urdf"):
        robot = os.fspath(body)
    else:
        task = load_task(body)
    if q is None:
        pairs: List[Tuple[str, float]] = []
    elif isinstance(q, Mapping):
        pairs = [(str(k), float(v)) for k, v in q.items()]
    else:
        names = task.joint_names if task is not None else _native.urdf_joint_names(os.fspath(body))
        a = np.asarray(q, dtype=np.float64).reshape(-1)
        if a.shape[0] != len(names):
            raise Error(f"q: a posture needs {len(names)} joint angles (body order), got {a.shape[0]}")
        pairs = list(zip(names, a.tolist()))
    doc = json.loads(
        _native.statics(
            robot,
            task,
            frame,
            pairs,
            None if hand_load_kg is None else float(hand_load_kg),
            _vec3("hand_force", hand_force),
            _vec3("gravity", gravity),
        )
    )
    doc["position_m"] = np.asarray(doc["position_m"], dtype=np.float64)
    joints = doc["joints"]
    doc["joint_names"] = [j["name"] for j in joints]
    for k in ("q_rad", "gravity_torque_nm", "load_torque_nm", "torque_nm"):
        doc[k] = np.array([j[k] for j in joints], dtype=np.float64)
    # the JSON's jacobian is three rows (x, y, z) with one column per joint
    doc["jacobian_matrix"] = np.asarray(doc["jacobian"], dtype=np.float64).reshape(3, len(joints))
    return doc
