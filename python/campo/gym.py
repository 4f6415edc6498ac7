"""Gymnasium environments over campo's closed loop (docs/python.md, "Gymnasium environments").

    import gymnasium, campo.gym
    env = gymnasium.make("campo/Navigate-v0", action_mode="velocity")
    obs, info = env.reset(seed=4)
    obs, reward, terminated, truncated, info = env.step(env.action_space.sample())

    envs = campo.gym.make_vec("campo/Navigate-v0", num_envs=8)   # stepped in C++ threads

One vehicle of a scene (its first, or `vehicle=`) is driven by normalised
actions toward its mission's waypoints; any other vehicles fly their scene's
planners. Only this module imports Gymnasium; the rest of campo does not need it.
"""

from __future__ import annotations

import numpy as np

try:
    import gymnasium
    from gymnasium import spaces
    from gymnasium.vector import AutoresetMode, VectorEnv
    from gymnasium.vector.utils import batch_space
except ImportError as error:  # pragma: no cover - the message is the point
    raise ImportError(
        "campo.gym needs Gymnasium (pip install 'gymnasium>=1.0', or pip install 'campo[gym]'); the rest of campo "
        "works without it"
    ) from error

from . import _campo

__all__ = ["NavigationEnv", "NavigationVectorEnv", "make_vec", "save_video", "ACTION_MODES", "DEFAULT_SCENES"]

#: The action modes of each vehicle type, its default first (docs/python.md, "Action modes").
ACTION_MODES = {
    "quadrotor": ("waypoint", "velocity", "attitude_thrust", "rotors"),
    "rover": ("waypoint", "twist", "wheels"),
}

#: The scene of each registered id.
DEFAULT_SCENES = {
    "campo/Navigate-v0": "trees_rolling_terrain",
    "campo/RoverNavigate-v0": "vineyard",
}


def _observation_space(native) -> spaces.Dict:
    entries = {}
    for key, size in native.state_keys:
        low, high = (-1.0, 1.0) if key == "orientation_wxyz" else (-np.inf, np.inf)
        entries[key] = spaces.Box(low, high, (size,), np.float32)
    for key, rows, cols, max_range_m in native.sensors:
        entries[key] = spaces.Box(0.0, np.float32(max_range_m), (rows, cols), np.float32)
    for key, rows, cols in native.cameras:  # "<alias>_rgb": RGB, row 0 at the top
        entries[key] = spaces.Box(0, 255, (rows, cols, 3), np.uint8)
    for key in native.imus:  # "<alias>_imu": specific force x, y, z (m/s²), angular rate x, y, z (rad/s)
        entries[key] = spaces.Box(-np.inf, np.inf, (6,), np.float32)
    return spaces.Dict(entries)


def _split_options(kwargs):
    """The keyword arguments the native environment reads (the rest are Python's)."""
    return {k: v for k, v in kwargs.items() if v is not None}


class NavigationEnv(gymnasium.Env):
    """One vehicle of a campo scene driven toward its mission's waypoints.

    scene: a scene file or a bundled scene's name. action_mode: see ACTION_MODES (default: waypoint).
    reward_fn: None for the weighted default (progress_weight, goal_reward, collision_penalty,
    time_penalty_per_s keywords), or a callable reward_fn(info, obs) -> float over the step's info
    (progress_m, reached, collided, dt_s, ...). overrides: {JSON pointer: value} applied to the scene
    of every episode; reset(options={"overrides": {...}}) adds some for one episode. Other keywords:
    vehicle, ticks_per_step, goal_radius_m, waypoint_range_m, waypoint_speed_mps, max_speed_mps,
    max_yaw_rate_radps (docs/python.md).
    """

    metadata = {"render_modes": ["rgb_array"], "render_fps": 10}

    def __init__(self, scene: str = "trees_rolling_terrain", *, action_mode: str = "waypoint",
                 render_mode: str | None = None, reward_fn=None, overrides: dict | None = None,
                 render_size: tuple[int, int] = (640, 480), render_camera: str = "chase",
                 render_distance_m: float = 6.0, **options):
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise ValueError(f"render_mode: one of {self.metadata['render_modes']} or None, got {render_mode!r}")
        if render_camera not in ("chase", "above"):
            raise ValueError(f"render_camera: \"chase\" or \"above\", got {render_camera!r}")
        if not render_distance_m > 0:
            raise ValueError(f"render_distance_m: a distance > 0, got {render_distance_m!r}")
        self._native = _campo._NavigationEnv(scene, overrides, action_mode=action_mode, **_split_options(options))
        self.scene = scene
        self.render_mode = render_mode
        self.render_size = tuple(render_size)
        self.render_camera = render_camera
        self.render_distance_m = float(render_distance_m)
        self.reward_fn = reward_fn
        self.vehicle_type = self._native.vehicle_type
        self.action_mode = self._native.action_mode
        #: The physical meaning of each action component, e.g. ("forward_mps", ...).
        self.action_names = tuple(self._native.action_names)
        self.observation_space = _observation_space(self._native)
        self.action_space = spaces.Box(-1.0, 1.0, (len(self.action_names),), np.float32)
        self.metadata = dict(self.metadata, render_fps=1.0 / self._native.step_s)
        #: Simulated seconds one step lasts.
        self.step_s = self._native.step_s
        self._last_obs = None

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        """A new episode. seed reseeds the environment's generator, which draws each episode's world seed
        (sensor and state noise); without one, the generator goes on (seed 0 at construction)."""
        super().reset(seed=seed)
        overrides = (options or {}).get("overrides")
        obs = self._native.reset(seed, overrides)
        self._last_obs = obs
        return obs, {}

    def step(self, action):
        action = np.ascontiguousarray(action, dtype=np.float32).reshape(self.action_space.shape)
        obs, reward, terminated, truncated, info = self._native.step(action)
        if self.reward_fn is not None:
            reward = float(self.reward_fn(info, obs))
        self._last_obs = obs
        return obs, float(reward), bool(terminated), bool(truncated), info

    def render(self):
        """An RGB frame (H x W x 3 uint8) of the vehicle and its track so far, from render_distance_m behind
        and half that above it (render_camera "chase") or straight above it ("above"); None unless
        render_mode is "rgb_array"."""
        if self.render_mode != "rgb_array":
            return None
        width, height = self.render_size
        return self._native.render(width, height, self.render_camera, self.render_distance_m)


class NavigationVectorEnv(VectorEnv):
    """num_envs NavigationEnvs stepped together in C++ worker threads, the interpreter released.

    Takes NavigationEnv's keywords, plus num_threads (default: the machine's cores) and
    autoreset_mode: Gymnasium's next-step mode (the default: the step after an episode ended resets
    it, its action ignored, reward 0, info's masks False for it) or its disabled mode (an ended
    environment idles, not stepped, until reset(options={"reset_mask": mask}) resets it).
    reset(seed=s) seeds environment i with s + i, so it reproduces NavigationEnv(...).reset(seed=s + i)
    exactly; options={"overrides": ...} takes one dict for all or a list of one per environment.
    Observations are new arrays every step, written by the workers directly from the sensors' buffers.
    """

    metadata = {"render_modes": [], "autoreset_mode": AutoresetMode.NEXT_STEP}

    def __init__(self, scene: str = "trees_rolling_terrain", num_envs: int = 1, *, num_threads: int = 0,
                 autoreset_mode=AutoresetMode.NEXT_STEP, action_mode: str = "waypoint", reward_fn=None,
                 overrides: dict | None = None, render_mode: str | None = None, **options):
        if render_mode is not None:
            raise ValueError("NavigationVectorEnv does not render: render one NavigationEnv instead")
        autoreset_mode = AutoresetMode(autoreset_mode) if isinstance(autoreset_mode, str) else autoreset_mode
        if autoreset_mode not in (AutoresetMode.NEXT_STEP, AutoresetMode.DISABLED):
            raise ValueError(f"autoreset_mode: AutoresetMode.NEXT_STEP or DISABLED, got {autoreset_mode!r}")
        self._native = _campo._NavigationBatch(scene, num_envs, num_threads,
                                               autoreset_mode == AutoresetMode.NEXT_STEP, overrides,
                                               action_mode=action_mode, **_split_options(options))
        self.scene = scene
        self.num_envs = num_envs
        self.reward_fn = reward_fn
        self.render_mode = None
        self.vehicle_type = self._native.vehicle_type
        self.action_mode = self._native.action_mode
        self.action_names = tuple(self._native.action_names)
        self.single_observation_space = _observation_space(self._native)
        self.single_action_space = spaces.Box(-1.0, 1.0, (len(self.action_names),), np.float32)
        self.observation_space = batch_space(self.single_observation_space, num_envs)
        self.action_space = batch_space(self.single_action_space, num_envs)
        self.step_s = self._native.step_s
        self.num_threads = self._native.num_threads
        self.metadata = dict(self.metadata, render_fps=1.0 / self.step_s, autoreset_mode=autoreset_mode)

    def reset(self, *, seed: int | list | None = None, options: dict | None = None):
        if seed is None:
            seeds = [None] * self.num_envs
        elif isinstance(seed, (int, np.integer)):
            seeds = [int(seed) + i for i in range(self.num_envs)]
        else:
            seeds = list(seed)
            if len(seeds) != self.num_envs:
                raise ValueError(f"reset: {self.num_envs} seeds, got {len(seeds)}")
        if seed is not None:
            self._np_random, self._np_random_seed = gymnasium.utils.seeding.np_random(
                seed if isinstance(seed, (int, np.integer)) else None)
        options = options or {}
        mask = options.get("reset_mask")
        if mask is not None:
            mask = [bool(m) for m in np.asarray(mask, dtype=bool).reshape(-1)]
        return self._native.reset(seeds, options.get("overrides"), mask)

    def step(self, actions):
        actions = np.ascontiguousarray(actions, dtype=np.float32).reshape(self.action_space.shape)
        obs, rewards, terminated, truncated, info = self._native.step(actions)
        if self.reward_fn is not None:
            rewards = np.where(info["_progress_m"], np.asarray(self.reward_fn(info, obs), dtype=np.float64), 0.0)
        return obs, rewards, terminated, truncated, info


def make_vec(env_id: str = "campo/Navigate-v0", num_envs: int = 1, **kwargs) -> NavigationVectorEnv:
    """The vector environment of a registered id (its scene unless scene= is given), stepped in C++ threads."""
    spec = gymnasium.spec(env_id)
    merged = dict(spec.kwargs)
    merged.update(kwargs)
    return NavigationVectorEnv(num_envs=num_envs, **merged)


def save_video(frames, path, fps: float) -> None:
    """Writes RGB frames (H x W x 3 uint8, e.g. from render()) to an MP4 or GIF with ffmpeg."""
    _campo._save_video([np.ascontiguousarray(f, dtype=np.uint8) for f in frames], str(path), float(fps))


def _register() -> None:
    for env_id, scene in DEFAULT_SCENES.items():
        if env_id in gymnasium.registry:
            continue
        gymnasium.register(id=env_id, entry_point="campo.gym:NavigationEnv",
                           vector_entry_point="campo.gym:NavigationVectorEnv", kwargs={"scene": scene})


_register()
