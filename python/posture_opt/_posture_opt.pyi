"""Type stubs of the compiled part of posture_opt (PyO3). Use the wrappers in ``posture_opt``:
these functions take validated arguments and return JSON text and float64 bytes."""

from typing import Any, Dict, List, Optional, Sequence, Tuple

__version__: str
HOLD_RULE: str
DEFAULT_CAPACITY_FLOOR: float
RANKING_RULE: str
MAX_LOAD_KG: float

class Error(ValueError):
    """Bad input: a task file, recording, option or shard result the library refused. The
    message is the command line's (it names the file, field, line or option)."""

class PlanningError(RuntimeError):
    """The optimiser failed on a validated task (the command line's exit code 1)."""

class Task:
    """A validated task: body, worker, workstation, phases, fatigue parameters.

    Make one with ``posture_opt.load_task`` (a file, a dict or YAML text) or
    ``posture_opt.default_setup`` (the generated worker, for evaluating recordings)."""

    @property
    def name(self) -> str:
        """The task's title."""
    @property
    def path(self) -> str:
        """The file (or the name given for a dict or YAML text)."""
    @property
    def robot(self) -> str:
        """The URDF used (a path, or "generated from worker")."""
    @property
    def joint_names(self) -> List[str]:
        """Joint names in q order (the column order of ``q`` arrays)."""
    @property
    def nq(self) -> int:
        """Number of joint coordinates."""
    @property
    def half_joint_ids(self) -> List[str]:
        """Half-joint ids (muscle groups) in order, as in results' ``half_joint_ids``."""
    @property
    def groups(self) -> List[str]:
        """The muscle groups in words, ordered like ``half_joint_ids``."""
    @property
    def phases(self) -> List[str]:
        """Phase names of one cycle, in order."""
    @property
    def cycles(self) -> int: ...
    @property
    def rest_s(self) -> float:
        """Rest at the end of each cycle [s]."""
    @property
    def cycle_s(self) -> float:
        """Length of one cycle [s]."""
    @property
    def duration_s(self) -> float:
        """Planned duration of the whole task [s]."""
    @property
    def gravity_m_s2(self) -> Tuple[float, float, float]:
        """Gravity [m/s²], world frame."""
    @property
    def hand_frames(self) -> Tuple[Optional[str], Optional[str]]:
        """Hand frames (right, left); None for a hand the body lacks."""
    @property
    def standing(self) -> bool:
        """Whether the body stands on its feet."""
    @property
    def fatigue_parameters(self) -> str:
        """The fatigue parameter set used."""
    @property
    def worker(self) -> Dict[str, Any]:
        """The worker: sex, stature_m, mass_kg, strength_percentile."""
    def to_dict(self) -> Optional[Dict[str, Any]]:
        """The task file as a dict (defaults filled in); None for a ``default_setup`` task."""

class _Evaluator:
    def __init__(
        self, task: Task, degrees: bool = False, hand_load_kg: Tuple[float, float] = (0.0, 0.0), source: str = "stream"
    ) -> None: ...
    def push(
        self, t: float, q: Sequence[float], right_force: Optional[Sequence[float]] = None, left_force: Optional[Sequence[float]] = None
    ) -> int: ...
    def push_many(self, t: bytes, q: bytes, force: bytes, force_given: Tuple[bool, bool]) -> int: ...
    def capacity(self) -> bytes: ...
    def fatigue_u_min(self) -> bytes: ...
    def load(self) -> bytes: ...
    def last_events(self, n: int) -> str: ...
    def events(self) -> str: ...
    @property
    def samples(self) -> int: ...
    @property
    def t_s(self) -> Optional[float]: ...
    def document(self) -> str: ...

def task_from_file(path: str) -> Task: ...
def task_from_yaml(text: str, path: str) -> Task: ...
def default_setup(
    sex: str, stature_m: float, mass_kg: float, strength_percentile: float, parameters: Optional[str] = None
) -> Task: ...
def plan(task: Task, adapt: bool = True, fatigue_only: bool = False, capacity_floor: float = 0.7, zones: bool = True) -> str: ...
def compare(
    tasks: Sequence[Task],
    names: Sequence[str],
    adapt: bool = True,
    fatigue_only: bool = False,
    capacity_floor: float = 0.7,
    shard: Optional[str] = None,
    threads: Optional[int] = None,
) -> str: ...
def merge_compare(shards: Sequence[Tuple[str, str]]) -> str: ...
def sweep(
    task: Task,
    sample: Optional[int] = None,
    seed: int = 1,
    adapt: bool = True,
    fatigue_only: bool = False,
    capacity_floor: float = 0.7,
    shard: Optional[str] = None,
    threads: Optional[int] = None,
) -> str: ...
def merge_sweep(shards: Sequence[Tuple[str, str]]) -> str: ...
def evaluate_file(
    task: Task,
    recording: str,
    mapping: Optional[str] = None,
    degrees: bool = False,
    hand_load_kg: Tuple[float, float] = (0.0, 0.0),
) -> str: ...
def evaluate_arrays(
    task: Task,
    t: bytes,
    q: bytes,
    force: bytes,
    force_given: Tuple[bool, bool],
    degrees: bool = False,
    hand_load_kg: Tuple[float, float] = (0.0, 0.0),
    source: str = "arrays",
) -> Tuple[str, bytes, bytes, bytes]: ...
def statics(
    robot: Optional[str] = None,
    task: Optional[Task] = None,
    frame: Optional[str] = None,
    q: Sequence[Tuple[str, float]] = ...,
    hand_load_kg: Optional[float] = None,
    hand_force: Optional[Sequence[float]] = None,
    gravity: Optional[Sequence[float]] = None,
) -> str: ...
def urdf_joint_names(robot: str) -> List[str]: ...
def task_schema() -> str: ...
