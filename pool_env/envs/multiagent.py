"""Two players at one table under the rules (PettingZoo AEC), and one against a fixed policy.

Both are thin fronts over the decision process (:func:`pool_env.game.step.step` with
``GameConfig.players == 2``): the rules, ball in hand, the break and the turns are the
game's (:mod:`pool_env.game.games`: ``"nine"``, ``"ten"``, ``"eight"``, ``"snooker"`` (a
frame) or ``"three_cushion"`` (a match)), the action and observation those of the game ids
(:class:`pool_env.PoolEnv` with that ``game``), seen from each agent's seat. What follows
describes the WPA games; snooker's and three-cushion's turns are on their docs pages.

``PoolDuelEnv(game="nine" | "ten" | "eight")``: ``player_0`` breaks (the cue ball in hand
behind the head string); the players alternate as the rules decide (a player keeps the
table after a legal shot that pots, the opponent comes to the table after a miss or a foul,
with ball in hand after a foul). In 9-ball and 10-ball the shot after a legal break may be
a push-out, and the opponent then has the option: the next agent selected is the one who
decides, with its action's option component, whether to shoot or hand the table back
(then the pusher is selected again). The rack ends with a win (+1 to the winner, -1 to
the loser) or is truncated after ``max_shots`` steps (0 to both).

Action (the game id's): aim, speed, cue ball x and y (used only with the cue ball in
hand), called pocket (used when shooting at the 8 and on every 10-ball shot), 10-ball's
called ball, 9-ball and 10-ball's option; see :class:`pool_env.PoolEnv`; then, on the spin
table (the default), the cue tip's side and vertical offsets.
Every default is the game's id's (``pool_env/NineBallGame-v2``, ...): its registered
arguments but the model, :func:`pool_env.game.config.make_config`'s defaults for the rest
(the spin table of every front, :data:`pool_env.game.sections.DEFAULT_MODEL`; ``"cut"``
aim, 0.45 .. 4.5 m/s, the break 8 .. 12 m/s), and its ``max_episode_steps`` as the shot
limit of the rack (both players' shots). ``model="roll"`` plays the roll ids' table
(``pool_env/NineBallGameRoll-v2``, ...): no tip columns. As on every front
(:func:`pool_env.game.sections.resolve`), a ``config`` given replaces these defaults
whole (its game is played: ``PoolDuelEnv(config=<a 10-ball config>)`` plays 10-ball), and
the keywords override either. ``end_on_foul`` is refused: it is the one-agent run-out
mode, and in a rack of two players a foul passes the table to the opponent.

Observation of each agent: the game ids' observation
(:func:`pool_env.game.kernels.observe.encode_rule_observations`) from that agent's seat:
the balls, the balls that agent may hit first, ball in hand, behind the head string, the
break, the open table, the agent's and the opponent's successive fouls, whether the
agent shoots next (9-ball and 10-ball: may push out, has the option).

``info``: the game ids' step info, ``winner`` as the agent's name (or
None while the rack is undecided).
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Mapping
from typing import Any, ClassVar

import gymnasium as gym
import numpy as np
from gymnasium import spaces
from numpy.typing import NDArray

from pool_env.envs.checks import check_seed
from pool_env.envs.registration import ENV_IDS, TASKS, roll_id, spin_id
from pool_env.envs.seeding import seed_table
from pool_env.extras import require
from pool_env.game import step as game_step
from pool_env.game.checks import check_actions, check_options
from pool_env.game.config import GameConfig, PoolConfig, make_config
from pool_env.game.info import potted_lookup, table_info
from pool_env.game.kernels.outcome import TRUNCATED
from pool_env.game.sections import resolve
from pool_env.game.state import GameState

AECEnv = require("pettingzoo", "multiagent", "pool_env.envs.multiagent").AECEnv
AGENTS = ("player_0", "player_1")
_ONE = np.zeros(1, dtype=np.intp)


def _game_ids(id_of: Callable[[str], str]) -> dict[str, tuple[dict[str, Any], int]]:
    """Each game's registered id ``id_of(task)``: its arguments and ``max_episode_steps``.

    The arguments less ``game`` and ``model``; a game's last task wins (SnookerFrame over
    SnookerBreak), and a task without that id (a spin-only one's roll twin) is skipped.
    """
    return {
        kwargs["game"]: ({k: v for k, v in kwargs.items() if k not in ("game", "model")}, steps)
        for kwargs, steps in (ENV_IDS[id_of(t)] for t in TASKS if id_of(t) in ENV_IDS)
        if "game" in kwargs
    }


#: The game ids' defaults: the table is every front's default, ``make_config``'s.
_GAME_IDS = _game_ids(spin_id)
#: The same from the roll twins, for ``model="roll"``: a game's own table there is its
#: roll table (snooker's preset less its spin-only values, as the roll id registers it).
#: A spin-only game has none, and its own refusal of the roll level speaks.
_GAME_ROLL_IDS = _game_ids(roll_id)
_OPTIONS = ("positions", "on_table", "rules")


def _rules_game(rules: Any) -> str | None:
    """The game a ``rules=`` argument names (a section or a mapping), if it names one."""
    if isinstance(rules, Mapping):
        return rules.get("game")
    return getattr(rules, "game", None)


class PoolDuelEnv(AECEnv):
    """Two agents play one rack, frame or match of a two-player game (module docstring).

    Args:
        game: ``"nine"``, ``"ten"``, ``"eight"``, ``"snooker"`` or ``"three_cushion"``;
            ``None``: the ``config``'s game, or ``"nine"`` without one. Beside a
            ``config``, a keyword override of its game.
        config: The sectioned config (:class:`pool_env.PoolConfig`), played as it is;
            ``None``: the game id's defaults (its scene, the spin table), truncated after
            the id's ``max_episode_steps`` shots of both players.
        **overrides: Keyword overrides of the config, as :class:`pool_env.PoolEnv` takes
            them (``table``, ``aim``, ``speed_range``, ``noise`` drawn from the generator
            seeded by ``reset(seed=...)``, ``break_speed_range``, ``max_shots``, ...).

    Raises:
        ValueError: On an unknown game or a bad argument (``end_on_foul=True`` among them).
    """

    metadata: ClassVar[dict[str, Any]] = {
        "render_modes": [],
        # PettingZoo's name carries the version: v1 since 9-ball's push-out and option (one
        # action column, two observation entries; push_out=False plays v0's 9-ball), v2 since
        # the spin table is the default (the two tip columns; model="roll" plays v1's spaces).
        "name": "pool_duel_v2",
        "is_parallelizable": False,
    }

    def __init__(
        self,
        game: str | None = None,
        config: PoolConfig | None = None,
        **overrides: Any,
    ) -> None:
        super().__init__()
        if game is not None and game not in _GAME_IDS:
            raise ValueError(f"game must be one of {sorted(_GAME_IDS)}, got {game!r}")
        if config is None:  # the game id's defaults, as gym.make would pass them
            # The game named, by game= or by the rules given (a conflict of the two is the
            # config's to refuse: game= goes in as the caller's override, not a default).
            name = game or _rules_game(overrides.get("rules")) or "nine"
            if name not in _GAME_IDS:
                raise ValueError(f"game must be one of {sorted(_GAME_IDS)}, got {name!r}")
            ids = _GAME_ROLL_IDS if overrides.get("model") == "roll" else _GAME_IDS
            registered, steps = ids.get(name, _GAME_IDS[name])
            defaults = {**registered, "game": name, "max_shots": steps}
            source = resolve(None, overrides if game is None else {"game": game, **overrides},
                             defaults)  # fmt: skip
        else:  # the config whole; a game given is the caller's override of its game
            source = resolve(config, overrides if game is None else {"game": game, **overrides})
        self.config: GameConfig = make_config(source, 2)
        self.possible_agents = list(AGENTS)
        self._action_space = spaces.Box(-1.0, 1.0, (self.config.action_size,), np.float32)
        self._observation_space = spaces.Box(-1.0, 1.0, (self.config.observation_size,), np.float32)
        self._state: GameState = self.config.new_state(1)
        seed_table(self._state, 0, None)
        self._lut = potted_lookup(self.config.n_object_balls)
        game_step.reset(self.config, self._state, _ONE)

    def observation_space(self, agent: str) -> spaces.Box:
        """The observation space (the same for both agents)."""
        return self._observation_space

    def action_space(self, agent: str) -> spaces.Box:
        """The action space (the same for both agents)."""
        return self._action_space

    @property
    def positions(self) -> NDArray[np.float64]:
        """``(N, 2)`` ball centres (m), cue first (a copy)."""
        return self._state.positions[0].copy()

    @property
    def rack(self) -> dict[str, Any]:
        """The rack state (the game's :meth:`~pool_env.game.ruleset.Ruleset.state_dict`)."""
        return self.config.ruleset.state_dict(self._state.rack[0])

    @property
    def shots(self) -> int:
        """Shots played in this rack."""
        return int(self._state.shots[0])

    def reset(self, seed: int | None = None, options: dict[str, Any] | None = None) -> None:
        """Rack the balls; ``player_0`` breaks with the cue ball in hand behind the head string.

        ``options={"positions": (N, 2), "on_table": (N,), "rules": {...}}`` starts instead
        from that layout (ball ``k`` in row ``k``, the cue ball on the table); without
        ``rules``: ``player_0`` to shoot, not a break, the cue ball where it lies, an open
        table (see :func:`pool_env.game.games.wpa.rack.rack_option`). Other keys are ignored, as
        PettingZoo's API test expects.

        Raises:
            ValueError: On a malformed or invalid layout (overlap, off the table, in a pocket).
        """
        if seed is not None:
            seed_table(self._state, 0, check_seed(seed))
        known = {k: v for k, v in check_options(options).items() if k in _OPTIONS}
        game_step.reset(self.config, self._state, _ONE, known)
        self.agents = list(self.possible_agents)
        self.rewards = {a: 0.0 for a in self.agents}
        self._cumulative_rewards = {a: 0.0 for a in self.agents}
        self.terminations = {a: False for a in self.agents}
        self.truncations = {a: False for a in self.agents}
        self.infos = {a: {} for a in self.agents}
        self.agent_selection = AGENTS[int(self.config.ruleset.shooters(self._state)[0])]

    def observe(self, agent: str) -> NDArray[np.float32]:
        """The observation of ``agent`` (a fresh array)."""
        viewer = np.array([AGENTS.index(agent)], dtype=np.int64)
        return game_step.observe(self.config, self._state, viewer)[0]

    def step(self, action: NDArray[np.float32] | None) -> None:
        """Play the selected agent's shot (or remove a finished agent, as AEC requires)."""
        agent = self.agent_selection
        if self.terminations[agent] or self.truncations[agent]:
            self._was_dead_step(action)
            return
        actions = check_actions(action, 1, single=True, width=self.config.action_size)
        result = game_step.step(self.config, self._state, _ONE, actions)
        info = table_info(result, self._lut)
        for term in self.config.ruleset.reward_terms:  # the practice rewards: not a duel's
            del info[f"reward_{term}"]
        winner = info["winner"]
        draw = winner == len(AGENTS)  # a drawn match (three-cushion's): 0 to each
        info["winner"] = None if winner < 0 or draw else AGENTS[winner]
        self._clear_rewards()
        self._cumulative_rewards[agent] = 0.0
        self.infos = {a: dict(info) for a in self.agents}
        if winner >= 0:
            for k, name in enumerate(AGENTS):
                self.rewards[name] = 0.0 if draw else 1.0 if k == winner else -1.0
                self.terminations[name] = True
        elif result.flags[0, TRUNCATED]:
            self.truncations = {name: True for name in self.agents}
        self.agent_selection = AGENTS[int(self.config.ruleset.shooters(self._state)[0])]
        self._accumulate_rewards()

    def render(self) -> None:
        """No rendering in this front (``render_modes`` is empty)."""

    def close(self) -> None:
        """Nothing to release."""


Policy = Callable[[NDArray[np.float32]], NDArray[np.float32]]


class VersusPolicyEnv(gym.Env[NDArray[np.float32], NDArray[np.float32]]):
    """One agent against a fixed opponent policy, as a single-agent Gymnasium env.

    The agent is ``player_0`` of a :class:`PoolDuelEnv` (so it breaks); after each of its
    shots the opponent plays its own shots (``opponent(observation) -> action``) until the
    table comes back or the rack ends. Reward: +1 for a won rack, -1 for a lost one, 0
    otherwise; the episode terminates when the rack is decided and is truncated after
    ``max_shots`` shots of both players. ``info`` is that of the agent's own shot (the
    keys of :class:`PoolDuelEnv`), plus ``opponent_shots``.

    Args:
        opponent: The opponent's policy (default: uniformly random actions from the env's
            generator).
        **kwargs: :class:`PoolDuelEnv` arguments.
    """

    metadata: ClassVar[dict[str, Any]] = {"render_modes": []}

    def __init__(self, opponent: Policy | None = None, **kwargs: Any) -> None:
        self.duel = PoolDuelEnv(**kwargs)
        self.opponent = opponent
        self.action_space = self.duel.action_space(AGENTS[0])
        self.observation_space = self.duel.observation_space(AGENTS[0])

    @property
    def config(self) -> GameConfig:
        """The duel's config (``pool_env.obs_layout(env)`` and the like read it)."""
        return self.duel.config

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[NDArray[np.float32], dict[str, Any]]:
        """Rack (or set up ``options``' layout) and return the agent's first observation.

        Raises:
            ValueError: On a bad seed or option, or when the opponent policy fails on the
                shots it plays first (``options["rules"]["shooter"] = 1``); the env is
                then as it was before the call.
        """
        seed = None if seed is None else check_seed(seed)
        undo = self._snapshot()
        super().reset(seed=seed)
        try:
            self.duel.reset(seed=None if seed is None else int(self.np_random.integers(2**31)),
                            options=options)  # fmt: skip
            self._opponent_plays()
        except BaseException:
            undo()
            raise
        return self.duel.observe(AGENTS[0]), {}

    def step(
        self, action: NDArray[np.float32]
    ) -> tuple[NDArray[np.float32], float, bool, bool, dict[str, Any]]:
        """The agent's shot, then the opponent's until the agent is back at the table.

        The step is all or nothing: when the opponent policy raises or returns an invalid
        action (NaN, a wrong shape, not numbers), the agent's shot and the opponent's
        shots before it are taken back (the table, the rack, the generators) and a
        ``ValueError`` names the opponent; the agent may step again.

        Raises:
            ValueError: On a bad action of the agent (before anything is played), after
                the rack is over, or when the opponent policy fails (as above).
        """
        if self._over():
            raise ValueError("the rack is over: call reset()")
        check_actions(action, 1, single=True, width=self.duel.config.action_size)
        undo = self._snapshot()
        try:
            self.duel.step(action)
            info = dict(self.duel.infos[AGENTS[0]])
            info["opponent_shots"] = self._opponent_plays()
        except BaseException:
            undo()
            raise
        return (
            self.duel.observe(AGENTS[0]),
            float(self.duel.rewards[AGENTS[0]]),
            bool(self.duel.terminations[AGENTS[0]]),
            bool(self.duel.truncations[AGENTS[0]]),
            info,
        )

    def _over(self) -> bool:
        duel = self.duel
        return duel.terminations[AGENTS[0]] or duel.truncations[AGENTS[0]]

    def _snapshot(self) -> Callable[[], None]:
        """A function that puts this env back as it is now (the duel and the generators)."""
        duel = self.duel
        restore_tables = duel._state.snapshot()
        names = ("agents", "rewards", "_cumulative_rewards", "terminations", "truncations",
                 "infos", "agent_selection")  # fmt: skip
        saved = {k: copy.deepcopy(duel.__dict__[k]) for k in names if k in duel.__dict__}
        rng, rng_seed = self._np_random, self._np_random_seed
        bits = None if rng is None else rng.bit_generator.state

        def restore() -> None:
            restore_tables()
            for k in names:
                duel.__dict__.pop(k, None)
            duel.__dict__.update(copy.deepcopy(saved))
            self._np_random, self._np_random_seed = rng, rng_seed
            if rng is not None:
                rng.bit_generator.state = bits

        return restore

    def _opponent_plays(self) -> int:
        """The opponent's shots until the agent is back at the table or the rack ends.

        Raises:
            ValueError: Naming the opponent, when its policy raises or returns an invalid
                action (the caller takes the step back).
        """
        shots = 0
        width = self.duel.config.action_size
        while self.duel.agent_selection == AGENTS[1] and not self._over():
            obs = self.duel.observe(AGENTS[1])
            if self.opponent is None:
                action = self.np_random.uniform(-1.0, 1.0, width).astype(np.float32)
            else:
                try:
                    raw = self.opponent(obs)
                except Exception as exc:
                    raise ValueError(
                        f"the opponent policy raised {exc!r} on its shot {shots + 1}: the "
                        "agent's shot was taken back, nothing was changed"
                    ) from exc
                try:
                    action = check_actions(raw, 1, single=True, width=width)[0]
                except ValueError as exc:
                    raise ValueError(
                        f"the opponent policy returned an invalid action on its shot "
                        f"{shots + 1} ({exc}): the agent's shot was taken back, nothing was "
                        "changed"
                    ) from None
            self.duel.step(action)
            shots += 1
        return shots
