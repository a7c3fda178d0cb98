"""A Gymnasium-style environment over trackbed.Simulation, without a Gymnasium
dependency: reset() -> (observation, info); step(action) -> (observation, reward,
terminated, truncated, info), as Gymnasium's Env has them.

    env = trackbed.gym.TrackbedEnv("scenes/outdoor.yaml", overrides={"duration_s": 20},
                                   reward=lambda obs, action, sim: -abs(action[0] - action[1]))
    obs, info = env.reset(seed=1)
    done = False
    while not done:
        obs, reward, terminated, truncated, info = env.step((0.4, 0.38))
        done = terminated or truncated
    info["metrics"]   # the episode's metrics.json

An action is (left_mps, right_mps). The episode ends when the run does: truncated
when it reached its duration, terminated when it stopped otherwise (a stall, a
diverged simulation). The reward hook is called after every step with the
observation, the action and the Simulation (for its localization and
report_estimate); without one the reward is 0.
"""
from . import Simulation


class TrackbedEnv:
    """One Simulation per episode. seed: the first episode's seed; later episodes
    count up from it unless reset() is given one. out: a folder that gets each
    episode's run folder as episode_NNNN; None: run folders are not kept."""

    def __init__(self, scenario_path, seed=1, overrides=None, reward=None, out=None,
                 images=True):
        self.scenario_path = scenario_path
        self.overrides = dict(overrides or {})
        self.reward = reward
        self.out = out
        self.images = images
        self._next_seed = seed
        self._episode = -1
        self.sim = None
        self.metrics = None

    def reset(self, seed=None, options=None):
        """Starts a new episode (ending the current one unscored) and returns the
        observation after its first step at standstill, and info."""
        if seed is not None:
            self._next_seed = seed
        self.close()
        self._episode += 1
        self.sim = Simulation(self.scenario_path, seed=self._next_seed,
                              overrides=self.overrides, images=self.images)
        self._next_seed += 1
        self.metrics = None
        obs = self.sim.step(0.0, 0.0)
        return obs, {"seed": self.sim.seed, "episode": self._episode}

    def step(self, action):
        if self.sim is None or self.metrics is not None:
            raise RuntimeError("step: call reset() first (the episode is over)")
        left, right = action
        obs = self.sim.step(left, right)
        reward = float(self.reward(obs, action, self.sim)) if self.reward else 0.0
        info = {"t": obs.t}
        terminated = truncated = False
        if self.sim.done:
            out = None
            if self.out is not None:
                out = f"{self.out}/episode_{self._episode:04d}"
            self.metrics = self.sim.finish(out=out)
            info["metrics"] = self.metrics
            truncated = self.metrics["stop_reason"] == "duration reached"
            terminated = not truncated
        return obs, reward, terminated, truncated, info

    def close(self):
        """Drops the current episode's simulation (its run folder is not kept)."""
        self.sim = None
