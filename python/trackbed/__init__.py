"""trackbed from Python: drive the simulated tracked robot with your own controller,
read its sensors as numpy arrays, score your own estimator beside the built-in ones.

    import trackbed
    sim = trackbed.Simulation("scenes/outdoor.yaml", seed=1, overrides={"duration_s": 20})
    while not sim.done:
        obs = sim.step(left_mps=0.4, right_mps=0.38)
    metrics = sim.finish(out="runs/py")

docs/python.md describes every name.
"""
import json

from ._trackbed import ScenarioError, _Simulation
from ._trackbed import read_image as _read_image
from ._trackbed import run as _run

__all__ = ["Simulation", "Observation", "Localization", "ScenarioError", "run", "read_image"]


def _override_value(value):
    """A Python value as the YAML text of `trackbed run --set key=value`."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if value is None:
        return "null"
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, str):
        return value
    if hasattr(value, "tolist"):  # numpy arrays and scalars
        value = value.tolist()
    return json.dumps(value)  # lists and maps: JSON is YAML flow style


def _overrides(overrides):
    if overrides is None:
        return []
    if not isinstance(overrides, dict):
        raise TypeError("overrides must be a dict of dotted keys to values, got "
                        + type(overrides).__name__)
    return [f"{key}={_override_value(value)}" for key, value in overrides.items()]


class Observation:
    """What the robot's sensors produced in one step, and the truth at its end.

    t            simulation time at the end of the step [s]
    encoders     the last encoder reading: int64 array [left_ticks, right_ticks]
    encoder_readings  every reading of the step: N x 3 (t, left_ticks, right_ticks)
    imu          the IMU samples of the step: N x 7 (t, gyro x y z [rad/s], accel x y z [m/s^2])
    stereo       None, or (left, right) uint8 arrays H x W: the step's last pair as the
                 localization stack sees it (after the camera's sensor model)
    stereo_t     the time of that pair [s], or None
    stereo_pairs every pair of the step: a list of (t, left, right)
    range_scan   None, or the ranges of the step's last scan [m] (numpy array)
    range_scans  every scan of the step: a list of (t, ranges_m, angles_rad)
    ground_truth T_world_body at t: 4 x 4 numpy array (for scoring and for controllers
                 that stand for a route, not for robot software)
    """

    __slots__ = ("t", "encoders", "encoder_readings", "imu", "stereo", "stereo_t",
                 "stereo_pairs", "range_scan", "range_scans", "ground_truth")

    def __init__(self, step):
        self.t = step["t"]
        self.encoder_readings = step["encoder_readings"]
        self.encoders = (self.encoder_readings[-1, 1:].astype("int64")
                         if len(self.encoder_readings) else None)
        self.imu = step["imu"]
        self.stereo_pairs = step["stereo_pairs"]
        last = self.stereo_pairs[-1] if self.stereo_pairs else None
        self.stereo = (last[1], last[2]) if last else None
        self.stereo_t = last[0] if last else None
        self.range_scans = step["range_scans"]
        self.range_scan = self.range_scans[-1][1] if self.range_scans else None
        self.ground_truth = step["ground_truth"]


class Localization:
    """The built-in localization stack's current estimates, T_world_body as 4 x 4 numpy
    arrays, or None when estimation is off (vo and fused also when the camera is off)."""

    def __init__(self, sim):
        self._sim = sim

    def fused(self):
        return self._sim.estimate("fused")

    def wheel(self):
        return self._sim.estimate("wheel")

    def wheel_noslip(self):
        return self._sim.estimate("wheel_noslip")

    def vo(self):
        return self._sim.estimate("vo")

    def ekf(self):
        return self._sim.estimate("ekf")


class Simulation:
    """One closed-loop run of a scenario, driven from Python one control period
    (1 / drive.rate_hz) at a time. The scenario needs no `drive` section.

    scenario_path  a scenario file (docs/scenario_format.md)
    seed           overrides the scenario's seed
    overrides      {dotted key: value}, as `trackbed run --set key=value`
    out            where the run folder is written while the run goes; None: a
                   temporary folder, moved to finish(out=...)
    images         return the stereo pairs in each Observation

    Errors raise exceptions carrying the command line's one-line messages:
    ScenarioError (a ValueError) for a bad file, key or value; ValueError for bad
    arguments; RuntimeError for a call out of turn (step after done, finish twice).
    """

    def __init__(self, scenario_path, seed=None, overrides=None, out=None, images=True):
        self._sim = _Simulation(str(scenario_path), seed, _overrides(overrides),
                                "" if out is None else str(out), bool(images))
        self.localization = Localization(self._sim)

    @property
    def done(self):
        """The run has ended (duration reached, stalled, diverged, or finished)."""
        return self._sim.done

    @property
    def t(self):
        """Simulation time at the end of the last step [s]."""
        return self._sim.t

    @property
    def scenario(self):
        """The resolved scenario as a dict: every key, defaults included
        (docs/scenario_format.md)."""
        return json.loads(self._sim.scenario_json)

    @property
    def seed(self):
        return self._sim.seed

    @property
    def duration_s(self):
        return self._sim.duration_s

    @property
    def control_period_s(self):
        """Simulated time of one step [s]: 1 / drive.rate_hz."""
        return self._sim.control_period_s

    def step(self, left_mps=0.0, right_mps=0.0):
        """Commands the track speeds [m/s] for one control period, simulates it and
        returns its Observation."""
        return Observation(self._sim.step(float(left_mps), float(right_mps)))

    def report_estimate(self, name, T_world_body):
        """Scores a 4 x 4 rigid transform as estimator `name`'s estimate at the current
        time, beside the built-in estimators: metrics.json estimators.<name>,
        <name>.tum, the plots."""
        self._sim.report_estimate(str(name), T_world_body)

    def finish(self, out=None):
        """Ends the run, writes its folder (to `out` when given) and returns
        metrics.json as a dict."""
        return json.loads(self._sim.finish("" if out is None else str(out)))


def read_image(path):
    """An 8-bit grayscale image file (the KITTI export's PNGs) as a uint8 array, H x W."""
    return _read_image(str(path))


def run(scenario_path, out, seed=None, overrides=None):
    """`trackbed run`: runs the scenario (its own drive, navigation or teach & repeat)
    into the run folder `out` and returns metrics.json as a dict."""
    return json.loads(_run(str(scenario_path), str(out), seed, _overrides(overrides)))
