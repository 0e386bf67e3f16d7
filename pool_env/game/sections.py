"""The environment's configuration as sections: table, task, noise, the game's rules and rewards.

Every front takes one :class:`PoolConfig` (``config=``, :func:`default_config` if none)
and keyword overrides, in the manner of MuJoCo Playground's ``default_config()`` with
overrides: ``PoolEnv(scene="one_ball", noise=(0.003, 0.05))`` is
``PoolEnv(config=default_config().override(scene="one_ball", noise=(0.003, 0.05)))``.
A keyword names a field of one section (:data:`KEYS` says which); a section's name takes
the section itself, or a mapping of its fields (``task={"scene": "one_ball"}``). Two
names are both a section and its main field: ``table`` (a :class:`~pool_env.Table` or
a dict of its arguments) and ``noise`` (the sigmas, or a noise model by name).

The sections hold the arguments as given, frozen (:func:`pool_env.game.frozen.freeze`: an
array or a dict given is copied, so that changing it afterwards changes no config);
:func:`pool_env.game.config.make_config` checks and parses them into the
:class:`~pool_env.game.config.GameConfig` the decision process runs on, which keeps its
:class:`PoolConfig` as ``source``.

Precedence, the one rule of every front (:func:`resolve`): the keywords a caller passes
override the config it passes, which replaces the registered id's defaults whole. A
Gymnasium id registers its defaults as one keyword, ``id_defaults``
(:mod:`pool_env.envs.registration`), so that a front tells them from the caller's own:
``gym.make("pool_env/OneBall-v1", config=cfg)`` plays ``cfg`` as it is (the id gives its
name and its ``TimeLimit``), ``gym.make("pool_env/OneBall-v1", config=cfg, noise=x)``
plays ``cfg`` with that noise, and ``gym.make("pool_env/OneBall-v1", noise=x)`` the id's
defaults with it.

The rules section belongs to the game: each ruleset names its own section type
(:attr:`pool_env.game.ruleset.Ruleset.section`), so ``end_on_foul`` exists where a
game has fouls, and ``game="nine"`` swaps the section for 9-ball's. So do the rewards: a
game names its reward terms and their default scales
(:attr:`~pool_env.game.ruleset.Ruleset.reward_terms`); the rewards section holds the scales
a user set (``reward_pot=2.0`` or ``rewards={"pot": 2.0}``), each checked against the
game's terms when the config is parsed.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, fields, replace
from typing import Any

from pool_env.game.frozen import FrozenMap, freeze_fields
from pool_env.game.noise import NoiseSpec
from pool_env.game.registry import every_game, ruleset_for
from pool_env.game.ruleset import RulesSection
from pool_env.game.scenes import SceneSpec
from pool_env.sim.table import Table

#: Default cue speed range (m/s): the shots real play uses, from Dr. Dave Alciatore's
#: "typical speeds" FAQ (slow 0.45-0.89, medium 0.89-1.9, fast 1.9-3.2, power 3.2-4.5 m/s;
#: ``docs/physics.md``). A soft touch rolls ~1 m, a power shot ~100 m if nothing stops it.
DEFAULT_SPEED_RANGE = (0.45, 4.5)

#: The model of the table played when the config gives none (no ``model``, and no
#: :class:`~pool_env.Table` or a dict of its arguments that names none): the spin table,
#: the one every ``pool_env/<Task>-v1`` id plays, so that ``PoolEnv()``, the vector and
#: two-player fronts and ``gym.make("pool_env/Pool-v1")`` play one table. Read here only,
#: by :func:`pool_env.game.config.make_config` (``tests/envs/test_front_defaults.py``);
#: the roll table is ``model="roll"`` (the ``<Task>Roll-v1`` ids).
DEFAULT_MODEL = "spin"


@dataclass(frozen=True)
class TableSection:
    """The table and its model level.

    Attributes:
        table: A :class:`~pool_env.Table`, a dict of its arguments (a config file), or
            ``None``: the default table, ``Table(model=DEFAULT_MODEL)`` (the spin table).
        model: ``"roll"`` or ``"spin"`` (every id sets it), or ``None``: a
            :class:`~pool_env.Table`'s own, else :data:`DEFAULT_MODEL` (``"spin"``).
    """

    table: Table | Mapping[str, Any] | None = None
    model: str | None = None

    def __post_init__(self) -> None:
        freeze_fields(self)


@dataclass(frozen=True)
class TaskSection:
    """The episode: the scene, how an action maps onto a shot, the rewards and the ends.

    Attributes:
        scene: A named scene (``"random"``, ``"one_ball"``, ``"nine_ball"``, ...), a list
            of ball positions, or a function of the generator (``pool_env.SCENES``).
        n_balls: Object balls of a random scene.
        rack_order: A rack scene's order of the balls: ``"random"`` (as the WPA rules rack
            them: the balls they place on their spots, the others drawn by each reset) or
            ``"fixed"`` (one order every episode; :mod:`pool_env.game.scenes`).
        aim: ``"cut"``, ``"relative"`` or ``"absolute"``: what ``action[0]`` means.
        aim_range: What ``action[0] = -1`` and ``+1`` map to (``None``: the aim's default).
        observation: ``"balls"`` (the balls' positions, and under rules the rack's state)
            or ``"shots"``: and per pocket the ghost-ball shot on the aim's reference ball
            (:mod:`pool_env.game.shot_features`).
        speed_range: Cue ball speeds (m/s) of ``action[1] = -1`` and ``+1``.
        tip_limit: Spin tables: the largest cue tip axis offset (fraction of ``R``);
            ``None``: a half-radius contact, the miscue limit.
        end_on_miss: A shot that pots nothing (or scratches) ends the episode.
        max_shots: Shots after which the episode is truncated, or ``None``.
    """

    scene: SceneSpec = "random"
    n_balls: int | None = None
    rack_order: str = "random"
    aim: str = "cut"
    aim_range: tuple[float, float] | None = None
    observation: str = "balls"
    speed_range: tuple[float, float] = DEFAULT_SPEED_RANGE
    tip_limit: float | None = None
    end_on_miss: bool = False
    max_shots: int | None = None

    def __post_init__(self) -> None:
        freeze_fields(self)


@dataclass(frozen=True)
class NoiseSection:
    """Execution noise: what the cue delivers against what the action asks.

    Attributes:
        sigmas: Gaussian sigmas ``(angle rad, speed m/s)``, on a spin table optionally
            ``(angle, speed, tip)`` (tip in fractions of ``R``); or a noise model by name,
            ``"fastfiz"`` or ``("fastfiz", k)`` (FastFiz's sigmas times ``k >= 0``, the
            computer billiards championships' model: :mod:`pool_env.game.noise`); or
            ``None``: no noise.
    """

    sigmas: NoiseSpec | None = None

    def __post_init__(self) -> None:
        freeze_fields(self)


@dataclass(frozen=True)
class RewardsSection:
    """The reward's scales by term: the game names its terms and their default scales.

    Attributes:
        scales: The scales set, by term (``{"pot": 2.0}``); a term left out keeps the
            game's default (:attr:`pool_env.game.ruleset.Ruleset.reward_terms`). Solitaire's
            terms are ``pot``, ``scratch``, ``no_contact`` and ``shaping``; the WPA games'
            ``pot``, ``foul`` and ``win``. The keyword ``reward_<term>`` sets one.
    """

    scales: Mapping[str, float] = field(default_factory=FrozenMap)

    def __post_init__(self) -> None:
        if not isinstance(self.scales, Mapping):
            raise ValueError(f"rewards must map term names to scales, got {self.scales!r}")
        freeze_fields(self)

    def __hash__(self) -> int:
        return hash(tuple(sorted(self.scales.items())))


@dataclass(frozen=True)
class PoolConfig:
    """One environment's arguments, by section (see the module docstring).

    Attributes:
        table: The :class:`TableSection`.
        task: The :class:`TaskSection`.
        noise: The :class:`NoiseSection`.
        rules: The game's rules section (``rules.game`` names the game).
        rewards: The :class:`RewardsSection`.
    """

    table: TableSection = field(default_factory=TableSection)
    task: TaskSection = field(default_factory=TaskSection)
    noise: NoiseSection = field(default_factory=NoiseSection)
    rules: RulesSection = field(default_factory=RulesSection)
    rewards: RewardsSection = field(default_factory=RewardsSection)

    def __post_init__(self) -> None:
        for name, section_type in _WHOLE.items():
            if not isinstance(getattr(self, name), section_type):
                raise ValueError(
                    f"{name} must be a {section_type.__name__}, got {getattr(self, name)!r}"
                )
        object.__setattr__(self, "rules", game_section(self.rules))

    def override(self, **overrides: Any) -> PoolConfig:
        """This config with ``overrides`` applied (see the module docstring).

        Raises:
            ValueError: On a name that is no key or section, a section of the wrong type,
                or a rule the config's game does not have.
        """
        config = self
        if "game" in overrides or "rules" in overrides:  # the game first: it owns the rest
            game = overrides.pop("game", _UNSET)
            config = config._with_rules(overrides.pop("rules", None), game)
        for name, value in overrides.items():
            config = config._with(name, value)
        return config

    def _with(self, name: str, value: Any) -> PoolConfig:
        if name in _WHOLE and isinstance(value, _WHOLE[name]):
            return replace(self, **{name: value})
        if name == "task" and isinstance(value, Mapping):
            return self._update("task", dict(value))
        if name == "noise" and isinstance(value, Mapping):
            return replace(self, noise=_section(NoiseSection, "noise", dict(value)))
        if name == "rewards" and isinstance(value, Mapping):
            return self._with_rewards(dict(value))
        if name.startswith(REWARD_PREFIX) and name[len(REWARD_PREFIX) :].isidentifier():
            return self._with_rewards({name[len(REWARD_PREFIX) :]: value})
        if name == "players":  # the front's: PoolEnv has one agent, PoolDuelEnv two
            raise ValueError("players is not an argument of PoolEnv: see pool_env.envs.multiagent")
        if name in _WHOLE and name not in KEYS:  # a section's name, given neither form
            raise ValueError(
                f"{name} must be a {_WHOLE[name].__name__} or a mapping of its keys, got {value!r}"
            )
        if name not in KEYS:
            if _is_rule_key(name):
                return self._with_rules({name: value}, _UNSET)
            raise ValueError(
                f"unknown config key {name!r}: use one of {sorted(KEYS)}, reward_<term>, a "
                f"rule key of the game or a section ({', '.join(SECTIONS)})"
            )
        section = KEYS[name]
        if section == "noise":
            return replace(self, noise=NoiseSection(sigmas=value))
        return self._update(section, {name: value})

    def _update(self, section: str, values: dict[str, Any]) -> PoolConfig:
        current = getattr(self, section)
        return replace(self, **{section: _section(type(current), section, values, current)})

    def _with_rewards(self, scales: dict[str, Any]) -> PoolConfig:
        if not all(isinstance(term, str) for term in scales):
            raise ValueError(f"rewards must map term names to scales, got {scales!r}")
        return replace(self, rewards=RewardsSection({**self.rewards.scales, **scales}))

    def _with_rules(self, rules: Any, game: Any) -> PoolConfig:
        values: dict[str, Any] = {}
        if isinstance(rules, RulesSection):
            _one_game(game, rules, rules.game)
            return replace(self, rules=rules)
        if isinstance(rules, Mapping):
            values = dict(rules)
        elif rules is not None:
            raise ValueError(f"rules must be a rules section or a mapping, got {rules!r}")
        if "game" in values:
            _one_game(game, rules, values["game"])
        name = values.pop("game", self.rules.game if game is _UNSET else game)
        # The reward scales were rule keys before they had a section of their own
        # (rules={"reward_foul": -2.0}): they are the rewards section's now.
        scales = {k[len(REWARD_PREFIX) :]: values.pop(k) for k in list(values)
                  if k.startswith(REWARD_PREFIX)}  # fmt: skip
        if scales:
            return self._with_rewards(scales)._with_rules({**values, "game": name}, _UNSET)
        section_type = ruleset_for(name).section
        current = self.rules if type(self.rules) is section_type else section_type()
        if current is not self.rules:  # another game's section: its options cannot carry over
            set_options = {
                f.name: getattr(self.rules, f.name)
                for f in fields(self.rules)
                if f.name != "game" and getattr(self.rules, f.name) != f.default
            }
            if set_options:
                raise ValueError(
                    f"game={name!r} replaces game {self.rules.game!r}, whose rules options "
                    f"{set_options} it has not: leave them out, or keep game "
                    f"{self.rules.game!r}"
                )  # fmt: skip
        for key in values:
            if key not in {f.name for f in fields(section_type)}:
                owners = [g for g, r in every_game().items() if key in _field_names(r.section)]
                raise ValueError(
                    f"{key} is a rule of game {' or '.join(map(repr, owners))}, not of "
                    f"game={name!r}"
                    if owners
                    else f"unknown rules key {key!r}: use {sorted(_field_names(section_type))}"
                )
        return replace(self, rules=replace(current, game=name, **values))


def resolve(
    config: PoolConfig | None,
    overrides: Mapping[str, Any],
    id_defaults: Mapping[str, Any] | None = None,
) -> PoolConfig:
    """The config a front plays: every front's one precedence rule (the module docstring).

    The caller's keywords (``overrides``) override the caller's ``config``; the defaults of
    the registered id (``id_defaults``, which ``gym.make`` passes) apply only when no
    ``config`` is given, in its place: a config is whole, every field of it a value its
    author chose (``end_on_miss=False`` as much as ``True``), so none of it is overridden
    by what an id registers.

    Args:
        config: The caller's config, or ``None``: the default, with ``id_defaults``.
        overrides: The caller's keywords (:meth:`PoolConfig.override`).
        id_defaults: The registered id's keywords (``None``: no id).

    Raises:
        ValueError: On a ``config`` that is no :class:`PoolConfig`, or a bad override.
    """
    if config is not None and not isinstance(config, PoolConfig):
        raise ValueError(f"config must be a pool_env.PoolConfig or None, got {config!r}")
    if id_defaults is not None and not isinstance(id_defaults, Mapping):
        raise ValueError(f"id_defaults must be a mapping of config keys, got {id_defaults!r}")
    if config is None:
        config = PoolConfig().override(**(id_defaults or {}))
    return config.override(**overrides)


def game_section(rules: RulesSection) -> RulesSection:
    """``rules`` as a section of its game's own type (:attr:`Ruleset.section`).

    A bare :class:`~pool_env.game.ruleset.RulesSection` names the game alone:
    ``RulesSection(game="nine")`` is 9-ball at its rules' defaults, ``WpaRules(game="nine")``.

    Raises:
        ValueError: On an unknown game, or a section of another game's type (its options
            would be dropped unread: ``WpaRules(game="solitaire", end_on_foul=True)``).
    """
    if not isinstance(rules, RulesSection):
        raise ValueError(f"rules must be a rules section or a mapping, got {rules!r}")
    section_type = ruleset_for(rules.game).section
    if type(rules) is section_type:
        return rules
    if type(rules) is RulesSection:
        return section_type(game=rules.game)
    owners = [repr(g) for g, r in every_game().items() if r.section is type(rules)]
    whose = f"the rules section of game {' or '.join(owners)}" if owners else "no game's"
    raise ValueError(
        f"rules={rules!r}: game={rules.game!r} takes a {section_type.__name__} (keys "
        f"{sorted(_field_names(section_type))}), and {type(rules).__name__} is {whose}"
    )


def _one_game(game: Any, rules: Any, named: Any) -> None:
    """Refuse ``game=`` beside a ``rules`` that names another game, whatever its form."""
    if game is not _UNSET and game != named:
        raise ValueError(f"game={game!r} but rules={rules!r} names game {named!r}: give one game")


def default_config(**overrides: Any) -> PoolConfig:
    """The default configuration, with keyword overrides.

    With none: solitaire on a random scene (3 object balls), on the default table, the spin
    table of the ``pool_env/<Task>-v1`` ids (:data:`DEFAULT_MODEL`), cut aim, 0.45 to 4.5
    m/s, no noise. Each key's default and meaning: ``docs/environments/specification.md``,
    "Configuration" (``help(pool_env.PoolEnv)`` too).

    Args:
        **overrides: Keys of one section each (:data:`KEYS` maps the shared ones):

            * table: ``table``, ``model``;
            * task: ``scene``, ``n_balls``, ``rack_order``, ``aim``, ``aim_range``,
              ``observation``, ``speed_range``, ``tip_limit``, ``end_on_miss``,
              ``max_shots``;
            * noise: ``noise``;
            * rules: ``game``, then the game's own keys (9-ball, 10-ball and 8-ball:
              ``end_on_foul``, ``break_speed_range``, ``push_out``; snooker:
              ``end_on_foul``; three-cushion: ``target``, ``inning_limit``,
              ``equalizing_inning``);
            * rewards: ``reward_<term>`` per reward term of the game.

            A section's name (``table``, ``task``, ``noise``, ``rules``, ``rewards``)
            takes the section whole or a mapping of its keys.

    Returns:
        The sectioned config, as given (:func:`pool_env.game.config.make_config` checks
        and parses it).

    Raises:
        ValueError: On a name that is no key or section, or a rule the game has not.

    Examples:
        >>> from pool_env import default_config
        >>> config = default_config(scene="one_ball", game="solitaire")
        >>> config.task.scene, config.rules.game
        ('one_ball', 'solitaire')
        >>> default_config(game="nine").rules.end_on_foul
        False
    """
    return PoolConfig().override(**overrides)


def _field_names(section_type: type) -> set[str]:
    return {f.name for f in fields(section_type)}


def _section(section_type: type, name: str, values: dict[str, Any], current: Any = None) -> Any:
    unknown = set(values) - _field_names(section_type)
    if unknown:
        raise ValueError(
            f"unknown {name} keys {sorted(unknown)}: use {sorted(_field_names(section_type))}"
        )
    return replace(current if current is not None else section_type(), **values)


_UNSET = object()  # "game" not given (None is a value, refused by the ruleset lookup)

#: The sections by name, in the order of :class:`PoolConfig`.
SECTIONS: tuple[str, ...] = ("table", "task", "noise", "rules", "rewards")

#: A keyword ``reward_<term>`` sets the scale of the game's reward term ``<term>``.
REWARD_PREFIX = "reward_"

#: Sections given whole, by name.
_WHOLE: dict[str, type] = {
    "table": TableSection,
    "task": TaskSection,
    "noise": NoiseSection,
    "rules": RulesSection,
    "rewards": RewardsSection,
}

#: Every keyword override of the shared sections and the section it sets (``noise`` sets
#: the noise's sigmas). Besides them: ``game``, ``reward_<term>`` (the rewards section) and
#: a rule key of some game (valid where the config's game has it).
KEYS: dict[str, str] = {
    **{f.name: "table" for f in fields(TableSection)},
    **{f.name: "task" for f in fields(TaskSection)},
    "noise": "noise",
}


def _is_rule_key(name: str) -> bool:
    """Whether ``name`` is a field of some game's rules section."""
    return any(name in _field_names(r.section) for r in every_game().values())
