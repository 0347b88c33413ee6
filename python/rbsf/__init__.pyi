"""rbsf: planning, simulation and execution for the RBSF intelligent jig (docs/python.md).

Type hints of the package rbsf: the classes and functions of the extension rbsf._rbsf
(python/src/*.cpp) and the helpers of __init__.py. State order q = (x, y, phi, theta,
l_1..l_m), tau = (tau_theta, tau_1..tau_m); SI units, angles in radians.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from typing import Any, Protocol, TypeAlias, overload

import numpy
from numpy.typing import ArrayLike, NDArray

#: Anything accepted where a Pose is asked for: a Pose or three numbers (x, y, phi).
PoseLike: TypeAlias = Pose | tuple[float, float, float] | Sequence[float]

class _CancelEvent(Protocol):
    def is_set(self) -> bool: ...

# Bad input

class InputError(ValueError):
    """Bad input (a cell key, an array's shape, a plan file): the library's message."""

# Cells, poses, the model and its analyses (bind_model.cpp)

class Finger:
    """One prismatic finger of a cell (read-only)."""

    @property
    def r(self) -> float:
        """Lateral offset along the base x axis [m]."""
    @property
    def stroke_min(self) -> float:
        """[m]"""
    @property
    def stroke_max(self) -> float:
        """[m]"""
    @property
    def mass(self) -> float:
        """Carriage mass [kg]."""
    @property
    def force_limit(self) -> float:
        """|tau_i| bound [N]."""

class Cell:
    """A jig cell: base, fingers, part, friction, sensing, uncertainty (read-only)."""

    @staticmethod
    def from_file(path: str) -> Cell:
        """Read a cell YAML file. Raises ValueError naming the key."""
    @staticmethod
    def from_yaml(text: str, label: str = "<cell>") -> Cell:
        """Read a cell from YAML (or JSON) text; `label` names it in messages."""
    @property
    def name(self) -> str: ...
    @property
    def gravity(self) -> float:
        """g0 [m/s^2]."""
    @property
    def fingers(self) -> list[Finger]: ...
    @property
    def num_fingers(self) -> int: ...
    @property
    def part_mass(self) -> float:
        """[kg]"""
    @property
    def part_inertia(self) -> float:
        """About the COM [kg m^2]."""
    @property
    def shape(self) -> str:
        """The part's shape type."""
    @property
    def mu_static(self) -> float: ...
    @property
    def mu_kinetic(self) -> float: ...
    @property
    def theta_limits(self) -> tuple[float, float]:
        """The base's angle limits [rad]."""
    @property
    def torque_limit(self) -> float: ...
    @property
    def senses_part(self) -> bool:
        """The cell measures the part's pose (else the joints only)."""

class Pose:
    """A part pose: COM (x, y) [m] in the world and angle phi [rad]."""

    @overload
    def __init__(self, x: float = 0.0, y: float = 0.0, phi: float = 0.0) -> None:
        """A pose from its three numbers; raises ValueError unless all are finite."""
    @overload
    def __init__(self, xyphi: Sequence[float]) -> None:
        """A pose from a sequence of three numbers (x, y, phi)."""
    x: float
    y: float
    phi: float
    def __iter__(self) -> Iterator[float]:
        """x, y, phi (so `x, y, phi = pose`)."""

class ContactReport:
    """One contact of a state's analysis."""

    @property
    def xi(self) -> float:
        """Boundary parameter."""
    @property
    def gap(self) -> float:
        """[m]"""
    @property
    def normal(self) -> NDArray[numpy.float64]:
        """Inward normal n_i (world)."""
    @property
    def f_n(self) -> float:
        """Phase-U normal force (eqs. 21-24) [N]."""
    @property
    def delta_n(self) -> float:
        """Phase-U normal acceleration [m/s^2]."""
    @property
    def alpha_n(self) -> float: ...
    @property
    def alpha_t(self) -> float:
        """Signed moment arm of the normal about the COM (eq. 25) [m]."""

class OmegaDotRange:
    """The part's angular accelerations reachable with every contact closed (section 3)."""

    @property
    def feasible(self) -> bool: ...
    @property
    def min(self) -> float:
        """[rad/s^2]"""
    @property
    def max(self) -> float:
        """[rad/s^2]"""
    @property
    def positive(self) -> bool: ...
    @property
    def negative(self) -> bool: ...

class Holding:
    """Static holding at rest (least-norm forces)."""

    @property
    def feasible(self) -> bool: ...
    @property
    def tau(self) -> NDArray[numpy.float64]: ...
    @property
    def f_n(self) -> NDArray[numpy.float64]: ...
    @property
    def f_t(self) -> NDArray[numpy.float64]: ...

class StateAnalysis:
    """Everything the model says about (q, v, tau)."""

    @property
    def contacts(self) -> list[ContactReport]: ...
    @property
    def accel(self) -> NDArray[numpy.float64]:
        """Phase-U accelerations (eq. 20)."""
    @property
    def sigma_min(self) -> float:
        """Smallest singular value of G1."""
    @property
    def determinate(self) -> bool: ...
    @property
    def phase(self) -> str:
        """C, P or U."""
    @property
    def phase_c_feasible(self) -> bool: ...
    @property
    def omega_dot(self) -> OmegaDotRange: ...
    @property
    def com_regions(self) -> list[tuple[int, int]]:
        """Contact pairs whose normals enclose the COM (paper Fig. 2)."""
    @property
    def com_in_end_region(self) -> bool: ...
    @property
    def holding(self) -> Holding: ...

class Model:
    """The model of one cell: kinematics, dynamics and analyses."""

    @overload
    def __init__(self, cell: Cell) -> None:
        """The model of a cell."""
    @overload
    def __init__(self, cell_file: str) -> None:
        """The model of a cell file."""
    @property
    def cell(self) -> Cell:
        """The cell (a copy)."""
    @property
    def num_fingers(self) -> int: ...
    @property
    def config_dim(self) -> int:
        """m + 4."""
    @property
    def control_dim(self) -> int:
        """m + 1."""
    def resting_configuration(self, pose: PoseLike, theta: float = 0.0) -> NDArray[numpy.float64]:
        """q with the part at `pose` and every finger placed under it at base angle theta."""
    def fingertip(self, q: ArrayLike, finger: int) -> NDArray[numpy.float64]:
        """Tip p_i in the world [m] (eq. 2)."""
    def mass_matrix(self, q: ArrayLike) -> NDArray[numpy.float64]:
        """M(q), (m + 4) x (m + 4)."""
    def bias(self, q: ArrayLike, v: ArrayLike) -> NDArray[numpy.float64]:
        """Q(q, v): gravity, Coriolis and centrifugal terms."""
    def energy(self, q: ArrayLike, v: ArrayLike) -> float:
        """Kinetic plus potential energy [J]."""
    def analyze(self, q: ArrayLike, v: ArrayLike, tau: ArrayLike) -> StateAnalysis:
        """Phase, determinacy, section-3 conditions and holding of a state, every finger touching."""

# The simulator (bind_simulator.cpp)

class SimulatorSettings:
    """Numerical settings of the simulator (simulator.h)."""

    def __init__(self) -> None: ...
    time_step: float
    """h [s]."""
    activation_distance: float
    contact_tolerance: float
    slip_tolerance: float
    regularization: float
    curvature_terms: bool
    drift_correction: bool
    max_mode_iterations: int

class SimState:
    """(t, q, v) and the contacts' memory; copy it to resume a run bit for bit."""

    def __init__(self, q: ArrayLike, v: ArrayLike | None = None) -> None:
        """At (q, v); v = 0 (at rest) by default."""
    @property
    def t(self) -> float:
        """[s]"""
    @property
    def q(self) -> NDArray[numpy.float64]: ...
    @property
    def v(self) -> NDArray[numpy.float64]: ...
    @property
    def modes(self) -> list[str]:
        """Each contact's friction memory: stick, slide or separated."""
    def copy(self) -> SimState: ...
    def __copy__(self) -> SimState: ...
    def __deepcopy__(self, memo: dict[int, Any], /) -> SimState: ...

class ContactStep:
    """What one step did at one contact."""

    @property
    def mode(self) -> str:
        """stick, slide or separated."""
    @property
    def f_n(self) -> float:
        """[N]"""
    @property
    def f_t(self) -> float:
        """[N]"""
    @property
    def gap(self) -> float:
        """[m]"""
    @property
    def slip(self) -> float:
        """[m/s]"""

class Samples:
    """Sampled states as arrays, row k sample k."""

    @property
    def t(self) -> NDArray[numpy.float64]:
        """(N,)"""
    @property
    def q(self) -> NDArray[numpy.float64]:
        """(N, m + 4)"""
    @property
    def v(self) -> NDArray[numpy.float64]:
        """(N, m + 4)"""
    @property
    def tau(self) -> NDArray[numpy.float64]:
        """(N, m + 1), held over the step ending there."""
    @property
    def f_n(self) -> NDArray[numpy.float64]:
        """(N, m) [N]"""
    @property
    def phase(self) -> NDArray[numpy.int8]:
        """(N,): 0 C, 1 P, 2 U, 3 unsupported (rbsf.PHASES)."""
    def __len__(self) -> int: ...

class Trajectory(Samples):
    """A rollout: Samples (row k is the state after step k, the input held over it, f_n and
    phase) and what the step did at the contacts."""

    @property
    def f_t(self) -> NDArray[numpy.float64]:
        """(N, m) [N]"""
    @property
    def slip(self) -> NDArray[numpy.float64]:
        """(N, m) [m/s]"""
    @property
    def mode(self) -> NDArray[numpy.int8]:
        """(N, m): 0 stick, 1 slide, 2 separated (rbsf.MODES)."""
    @property
    def final_state(self) -> SimState:
        """The state after the last step."""
    @property
    def fell_at(self) -> float:
        """Time the part fell off the fingers and the run stopped [s]; -1: never."""

class Simulator:
    """The hybrid contact simulator: stick, slip, separation and renewed contact."""

    def __init__(self, model: Model, settings: SimulatorSettings = ...) -> None: ...
    @property
    def settings(self) -> SimulatorSettings:
        """The settings (a copy)."""
    def step(self, state: SimState, tau: ArrayLike) -> tuple[list[ContactStep], str]:
        """Advance `state` (in place) by one step with tau held; returns (contacts, phase)."""
    def rollout(
        self,
        start: SimState | ArrayLike,
        tau: ArrayLike,
        steps: Sequence[int] | NDArray[numpy.integer[Any]] = ...,
    ) -> Trajectory:
        """Hold row j of tau for steps[j] steps from `start`, in C++ without the GIL."""

# Plans, plan files, certificates and trials (bind_plan.cpp)

class PlanSegment:
    """tau held (or ramped) over whole steps."""

    @property
    def phase(self) -> str: ...
    @property
    def steps(self) -> int: ...
    @property
    def duration(self) -> float:
        """[s]"""
    @property
    def tau(self) -> NDArray[numpy.float64]: ...
    @property
    def tau_end(self) -> NDArray[numpy.float64] | None:
        """None: tau held; else tau ramps linearly to it."""
    @property
    def roles(self) -> str:
        """Each finger's role: S stick, + / - slide, L lifted, F free."""

class Plan:
    """A plan: tau segments and the trajectory they produce."""

    @property
    def status(self) -> str:
        """exact or approximate."""
    @property
    def planner(self) -> str: ...
    @property
    def seed(self) -> int: ...
    @property
    def goal_distance(self) -> float:
        """[tolerance units]"""
    @property
    def start(self) -> Pose: ...
    @property
    def goal(self) -> Pose: ...
    @property
    def start_theta(self) -> float: ...
    @property
    def joint_feedback(self) -> bool:
        """Held by the joints alone: its law feeds back the joints only."""
    @property
    def time_step(self) -> float:
        """[s]"""
    @property
    def q0(self) -> NDArray[numpy.float64]: ...
    @property
    def duration(self) -> float:
        """[s]"""
    @property
    def phase_sequence(self) -> str: ...
    @property
    def planned_phases(self) -> str: ...
    @property
    def pivots(self) -> int: ...
    @property
    def segments(self) -> list[PlanSegment]:
        """The segments (a new list on each access)."""
    @property
    def segment_starts(self) -> NDArray[numpy.float64]:
        """Each segment's start time [s]."""
    @property
    def samples(self) -> Samples:
        """The trajectory as arrays (built on each access)."""
    @property
    def sample_roles(self) -> list[str]:
        """Each sample's planned contact roles (its segment's): S, + / -, L, F."""

class TrialOutcome:
    """How one closed-loop trial ended."""

    @property
    def index(self) -> int: ...
    @property
    def success(self) -> bool: ...
    @property
    def failure(self) -> str: ...
    @property
    def position_error(self) -> float:
        """[m]"""
    @property
    def angle_error(self) -> float:
        """[rad]"""
    @property
    def dropped(self) -> bool: ...
    @property
    def dropped_time(self) -> float: ...
    @property
    def max_deviation(self) -> float: ...
    @property
    def phases(self) -> str: ...
    @property
    def end(self) -> str:
        """done, held, lost or off."""

class Certificate:
    """Closed-loop trials under the cell's sensing and uncertainty, judged by outcome."""

    @property
    def ran(self) -> bool: ...
    @property
    def certified(self) -> bool: ...
    @property
    def law(self) -> str: ...
    @property
    def trials(self) -> int: ...
    @property
    def successes(self) -> int: ...
    @property
    def success_rate(self) -> float: ...
    @property
    def lower_bound(self) -> float: ...
    @property
    def confidence(self) -> float: ...
    @property
    def required_rate(self) -> float: ...
    @property
    def seed(self) -> int: ...
    @property
    def worst(self) -> TrialOutcome: ...
    @property
    def verdict(self) -> str:
        """One line."""
    @property
    def report(self) -> str:
        """The tools' report."""

class CertificateSettings:
    """How a certificate is made (certificate.h)."""

    def __init__(self) -> None: ...
    trials: int
    """A fixed count; 0: sequential."""
    batch: int
    max_trials: int
    confidence: float
    required_rate: float
    seed: int
    threads: int
    """0: one per core."""
    open_loop: bool

class OptimizationSummary:
    """How a refinement went."""

    @property
    def ran(self) -> bool: ...
    @property
    def iterations(self) -> int: ...
    @property
    def cost_before(self) -> float: ...
    @property
    def cost_after(self) -> float: ...
    @property
    def chosen(self) -> bool: ...
    @property
    def message(self) -> str: ...

class PlanRecord:
    """A plan with its certificate and optimisation summary: what a plan file holds."""

    @property
    def plan(self) -> Plan: ...
    @property
    def certificate(self) -> Certificate: ...
    @property
    def optimization(self) -> OptimizationSummary: ...
    @staticmethod
    def read(path: str) -> PlanRecord:
        """Read a plan file. Raises ValueError naming the file and key."""
    @staticmethod
    def from_json(text: str) -> PlanRecord:
        """A plan file's text."""
    def to_json(self, reproducible: bool = False) -> str:
        """The plan file's text; reproducible leaves the wall-clock fields out."""
    def write(self, path: str, reproducible: bool = False) -> None:
        """Write the plan file atomically (complete or absent)."""

def certify(model: Model, plan: Plan, settings: CertificateSettings = ...) -> Certificate:
    """Certify `plan` on the model's cell: closed-loop trials on every core, GIL released."""

def replay_trial(
    model: Model, plan: Plan, index: int, settings: CertificateSettings = ...
) -> tuple[TrialOutcome, Samples]:
    """Trial `index` of a certificate again (-1: nominal): (outcome, true states)."""

def draw_trial(model: Model, plan: Plan, seed: int, index: int) -> dict[str, Any]:
    """The plant, start and actuators trial `index` of `seed` draws on the model's cell."""

# Planning and the benchmark suites (bind_pipeline.cpp)

class PlanEvent:
    """One event of a planning run, for progress callbacks."""

    @property
    def kind(self) -> str:
        """stage, search, plan found, refined or judged."""
    @property
    def text(self) -> str: ...
    @property
    def elapsed(self) -> float:
        """search: seconds so far."""
    @property
    def propagations(self) -> int: ...
    @property
    def best_distance(self) -> float:
        """search: tolerance units."""

class Problem:
    """A reorientation problem: start at rest, goal."""

    def __init__(
        self,
        start: PoseLike,
        goal: PoseLike,
        start_theta: float = 0.0,
        absolute_angle: bool = False,
        position_tolerance: float = 0.01,
        angle_tolerance: float = 0.03490658503988659,  # 2 degrees
    ) -> None: ...
    start: Pose
    goal: Pose
    start_theta: float
    absolute_angle: bool
    @property
    def position_tolerance(self) -> float:
        """[m]"""
    @property
    def angle_tolerance(self) -> float:
        """[rad]"""

class PlanSettings:
    """The pipeline's settings with plan-reorientation's defaults."""

    def __init__(self) -> None: ...
    method: str
    """auto (support, then KPIECE1), support, or KPIECE1, RRT, SST, EST, PDST."""
    time_limit: float
    """The searches' budget together [s]."""
    seed: int
    max_propagations: int
    """Kinodynamic propagations per search (0: none)."""
    decisive_modes: bool
    attempts: int
    """Kinodynamic searches at most (0: while the budget lasts)."""
    optimize: bool
    """Refine exact plans."""
    max_expansions: int
    """Support planner: expansions over all its searches (0: none)."""
    friction_uses: list[float]
    simple_turns: list[float]
    """Support planner: friction uses of the simple turns searched first."""
    knots: int
    optimize_time_limit: float
    optimize_iterations: int
    optimize_tolerance: float
    certificate: CertificateSettings

class Attempt:
    """One search and its plan's certificate."""

    @property
    def search(self) -> str:
        """support or kinodynamic."""
    @property
    def planner(self) -> str: ...
    @property
    def seed(self) -> int: ...
    @property
    def found(self) -> bool: ...
    @property
    def exact(self) -> bool: ...
    @property
    def refined(self) -> bool: ...
    @property
    def cancelled(self) -> bool: ...
    @property
    def search_time(self) -> float:
        """[s]"""
    @property
    def wall_time(self) -> float:
        """[s]"""
    @property
    def expansions(self) -> int: ...
    @property
    def phases(self) -> str: ...
    @property
    def certificate(self) -> Certificate: ...
    @property
    def note(self) -> str: ...
    @property
    def reach(self) -> str | None:
        """What a support search reached and the rule that stopped it."""

class PlanResult:
    """How a planning run ended."""

    @property
    def status(self) -> str:
        """certified, not certified, approximate, no plan or cancelled."""
    @property
    def certified(self) -> bool: ...
    @property
    def record(self) -> PlanRecord | None:
        """The plan kept with its certificate (None: no plan)."""
    @property
    def attempts(self) -> list[Attempt]: ...
    @property
    def chosen(self) -> int:
        """Index of the attempt kept (-1: none)."""
    @property
    def best_distance(self) -> float: ...
    @property
    def wall_time(self) -> float:
        """[s]"""

def plan(
    model: Model,
    problem: Problem,
    settings: PlanSettings = ...,
    progress: Callable[[PlanEvent], object] | None = None,
    cancel: _CancelEvent | None = None,
) -> PlanResult:
    """Plan, refine and certify on a worker thread; progress, cancel and Ctrl-C on this one."""

class BenchProblem:
    """One problem of a benchmark suite."""

    @property
    def name(self) -> str: ...
    @property
    def cell_path(self) -> str: ...
    @property
    def problem(self) -> Problem: ...

def load_problem_suite(path: str) -> list[BenchProblem]:
    """The problems of a benchmark suite file."""

# The controller facade (bind_controller.cpp)

class ExecutionStatus:
    """One tick's execution status; track() fills it in place."""

    def __init__(self) -> None: ...
    @property
    def plan_time(self) -> float:
        """[s]"""
    @property
    def position_deviation(self) -> float:
        """[m]"""
    @property
    def angle_deviation(self) -> float:
        """[deg]"""
    @property
    def stroke_deviation(self) -> float:
        """[m]"""
    @property
    def stroke_speed_deviation(self) -> float:
        """[m/s]"""
    @property
    def saturated(self) -> bool: ...
    @property
    def pose_seen(self) -> bool: ...
    @property
    def pose_age(self) -> float:
        """[s]"""
    @property
    def bad_readings(self) -> int: ...
    @property
    def flags(self) -> int:
        """ExecutionFlag bits."""
    @property
    def flags_text(self) -> str: ...
    @property
    def contact_open(self) -> str:
        """Relied-on contacts open, fingers counted from 1."""
    @property
    def verdict(self) -> str:
        """on plan, degraded, leaving, holding or done."""
    @property
    def hold_reason(self) -> str: ...
    @property
    def hold_time(self) -> float:
        """[s]"""

class Controller:
    """The cell controller's facade: publish a certified plan, then track() each period."""

    @overload
    def __init__(self, cell_file: str) -> None:
        """The controller of a cell file."""
    @overload
    def __init__(self, cell: Cell) -> None:
        """The controller of a cell."""
    def load_file(
        self, path: str, accept_uncertified: bool = False, accept_other_evidence: bool = False
    ) -> None:
        """Publish a plan file; raises ValueError with the reason when it is refused."""
    def load(
        self,
        record: PlanRecord,
        accept_uncertified: bool = False,
        accept_other_evidence: bool = False,
    ) -> None:
        """Publish a PlanRecord, as load_file()."""
    def track(
        self,
        t: float,
        joints: ArrayLike,
        out: NDArray[numpy.float64] | None = None,
        status: ExecutionStatus | None = None,
    ) -> NDArray[numpy.float64]:
        """tau for [t, t + h) from the joints measured at t; into `out` and `status` when given."""
    def track_log(
        self, times: ArrayLike, joints: ArrayLike
    ) -> tuple[NDArray[numpy.float64], NDArray[numpy.int8]]:
        """track() over a log in C++: (tau (N, m + 1), verdict codes (N))."""
    def add_part_pose(self, stamp: float, pose: PoseLike) -> None:
        """A part pose measured at plan time `stamp`."""
    def start(self) -> None:
        """The next track() starts the plan afresh."""
    def hold(self) -> None:
        """Bring the reference to rest on the plan's path."""
    def held_state(self) -> tuple[Pose, float] | None:
        """(pose, theta) where the held part is estimated; None when not holding."""
    @property
    def time_step(self) -> float:
        """The control period [s]."""
    @property
    def plan_id(self) -> int: ...
    def sample(self, t: float) -> dict[str, Any] | None:
        """The published plan's reference at t (t, q, v, tau, phase, roles); None when none."""
    @property
    def duration(self) -> float | None:
        """The published plan's duration [s]; None when none."""

# Pure-Python helpers (__init__.py)

#: The library's version (the CMake project's).
__version__: str

#: Phase codes of Trajectory.phase and Samples.phase.
PHASES: tuple[str, str, str, str]
#: Contact mode codes of Trajectory.mode.
MODES: tuple[str, str, str]

def deg(angle_degrees: float) -> float:
    """An angle in degrees as radians."""

def cell_from_dict(cell: dict[str, Any], label: str = "<dict>") -> Cell:
    """A Cell from a dict with the keys of a cell file; ValueError names the bad key."""

def load_cell_dict(path: str) -> dict[str, Any]:
    """A cell file as a dict (to change a key and build it with cell_from_dict)."""
