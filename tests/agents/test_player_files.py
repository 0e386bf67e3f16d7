"""Player files (the search player's ``.yaml``): a schema checked at load, one clear error.

A table of bad files, each written to a temporary folder beside copies of the committed
models, must raise one ``ValueError`` naming the file and the key (dotted under
``settings``) or the model path as written; the commands that take a player file turn it
into a usage error; the committed files load and play the shots they played before.
"""

from __future__ import annotations

import argparse
import re
import shutil
from dataclasses import replace
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

from agents.evaluation.duels import main as duels_main
from agents.evaluation.evaluate import main as evaluate_main
from agents.evaluation.players import check_agents, make_agent
from agents.evaluation.runouts import main as runouts_main
from agents.learned.layout_value import LayoutValue
from agents.learned.leaf_value import SetLeaf
from agents.learned.player_file import load_search_player, read_player_file
from agents.learned.search_player import SearchSettings
from agents.learned.set_value import SetValue

ENV_ID = "pool_env/NineBallGame-v2"
ROOT = Path(__file__).resolve().parents[2]
MODELS = ROOT / "models"
#: A good player file, the models beside it (the fixture copies them there).
GOOD = """\
kind: search
layout_value: runout_value.npz
duel_value: duel_value.npz
set_value: set_value.npz
settings:
  budget: 0.5
  samples: 4
"""
#: A directory that is not there: the model of that name lies beside the file instead.
GONE = Path("gone", "runout_value.npz").as_posix()


def _settings(line: str) -> str:
    """:data:`GOOD` with ``line`` under ``settings``, in place of the line of its key."""
    key = line.split(":")[0]
    return "".join(ln for ln in GOOD.splitlines(True) if not ln.startswith(f"  {key}:")) + (
        f"  {line}\n"
    )


def _swap(key: str, value: str) -> str:
    """:data:`GOOD` with ``key``'s line replaced (or dropped when ``value`` is None)."""
    lines = [ln for ln in GOOD.splitlines() if not ln.startswith(f"{key}:")]
    return "\n".join([*lines, f"{key}: {value}"] if value is not None else lines) + "\n"


#: (id, file text, what the message must name). The message is always prefixed by the file.
BAD = [
    ("misspelt top-level key", GOOD + "setvalue: set_value.npz\n", "unknown key setvalue"),
    ("unknown setting", _settings("plies: 3"), "unknown key settings.plies"),
    ("a list, not a mapping", "- kind: search\n- layout_value: runout_value.npz\n",
     "the file must be a mapping"),
    ("an empty file", "", "the file must be a mapping"),
    ("not YAML", "kind: [search\n", "cannot be read as YAML"),
    ("another kind", _swap("kind", "lookahead"), "kind must be 'search'"),
    ("no kind", _swap("kind", None), "kind must be 'search'"),
    ("no layout_value", _swap("layout_value", None), "layout_value is required"),
    ("layout_value a number", _swap("layout_value", "3"), "layout_value must be the path"),
    ("set_value empty", _swap("set_value", "''"), "set_value must be the path"),
    ("missing model", _swap("layout_value", "nothere.npz"), "layout_value 'nothere.npz' not"),
    ("no fallback beside the file", _swap("layout_value", GONE), f"layout_value '{GONE}' not"),
    ("npz without weights", _swap("layout_value", "noweights.npz"), "'weights'"),
    ("corrupt npz", _swap("duel_value", "corrupt.npz"), "duel_value 'corrupt.npz'"),
    ("truncated npz", _swap("layout_value", "truncated.npz"), "layout_value 'truncated.npz'"),
    ("an npy, not an npz", _swap("layout_value", "plain.npz"), "layout_value 'plain.npz'"),
    ("weights of the wrong size", _swap("layout_value", "short.npz"), "weights must be"),
    ("a layout value as the set network", _swap("set_value", "duel_value.npz"),
     "set_value 'duel_value.npz'"),
    ("settings a list", GOOD.split("settings:")[0] + "settings: [1, 2]\n",
     "settings must be a mapping"),
    ("settings null", GOOD.split("settings:")[0] + "settings:\n", "settings must be a mapping"),
    ("a count that is a float", _settings("finalists: 2.7"), "settings.finalists must be an"),
    ("a whole float count", _settings("round_samples: 8.0"), "settings.round_samples must be an"),
    ("a count that is a bool", _settings("next_samples: true"), "settings.next_samples must be"),
    ("a zero count", _settings("hand_samples: 0"),
     "settings.hand_samples must be an integer in [1, 16]"),
    ("a negative count", _settings("min_rounds: -1"), "settings.min_rounds must be an int"),
    ("a count past its bound", _settings("samples: 1000000000000"),
     "settings.samples must be an integer in [1, 512] (first ply: ~100 candidates x samples "
     "tables, ~5 KB each: a shot well under 1 GB), got 1000000000000"),
    ("hand spots past their bound", _settings("hand_spots: 201"),
     "settings.hand_spots must be an integer in [0, 200]"),
    ("an infinite budget", _settings("budget: .inf"), "settings.budget must be a finite num"),
    ("a negative budget", _settings("budget: -1.0"), "settings.budget must be a finite number > 0"),
    ("a NaN budget", _settings("budget: .nan"), "settings.budget must be a finite number"),
    ("a budget in quotes", _settings("budget: '1.0'"), "settings.budget must be a finite number"),
    ("a bool for a number", _settings("prune_z: true"), "settings.prune_z must be a finite number"),
    ("a negative prune_z", _settings("prune_z: -1.0"), "settings.prune_z must be a finite number"),
    ("a NaN break aim", _settings("break_cut: .nan"), "settings.break_cut must be a finite number"),
    ("a break aim past the 1", _settings("break_cut: 0.5"), "settings.break_cut must lie in"),
    ("a break off the table", _settings("break_y: 5.0"), "settings.break_y must lie in [-0.6064"),
    ("a break speed past 1", _settings("break_speed: 1.5"), "settings.break_speed"),
    ("a break tip of one number", _settings("break_tip: [0.0]"), "settings.break_tip must be two"),
    ("a NaN break tip", _settings("break_tip: [0.0, .nan]"), "settings.break_tip must be two"),
    ("a break tip string", _settings("break_tip: ab"), "settings.break_tip must be two"),
    ("a break tip past 1", _settings("break_tip: [0.0, 1.5]"), "settings.break_tip must be two"),
    # YAML keeps the last of two equal keys: the file must say each once, at any level.
    ("a setting twice, flow style",
     GOOD.split("settings:")[0] + "settings: {samples: 8, samples: 2}\n",
     "duplicate key settings.samples (twice on line 5)"),
    ("a setting twice, block style", GOOD + "  samples: 2\n",
     "duplicate key settings.samples (lines 7 and 8)"),
    ("a model path twice", GOOD + "layout_value: duel_value.npz\n",
     "duplicate key layout_value (lines 2 and 8)"),
    ("a directory as the model", _swap("layout_value", "folder"),
     "layout_value 'folder' is a directory, not a file"),
    ("weights as strings", _swap("layout_value", "text.npz"), "array 'weights' must hold real"),
    ("weights as complex numbers", _swap("duel_value", "complex.npz"),
     "got dtype complex128"),
    ("weights as bools", _swap("layout_value", "bool.npz"), "got dtype bool"),
]  # fmt: skip


@pytest.fixture(scope="module")
def env() -> gym.Env:
    return gym.make(ENV_ID)


@pytest.fixture
def folder(tmp_path: Path) -> Path:
    """A folder with the committed models and broken ones beside them."""
    for name in ("runout_value.npz", "duel_value.npz", "set_value.npz"):
        shutil.copy(MODELS / name, tmp_path / name)
    np.savez(tmp_path / "noweights.npz", w=np.zeros(12))
    np.savez(tmp_path / "short.npz", weights=np.zeros(3))
    (tmp_path / "corrupt.npz").write_bytes(b"not an archive at all")
    (tmp_path / "truncated.npz").write_bytes((MODELS / "duel_value.npz").read_bytes()[:60])
    weights = LayoutValue.load(MODELS / "runout_value.npz").weights  # of the right size
    for name, dtype in (("text", str), ("complex", complex), ("bool", bool)):
        np.savez(tmp_path / f"{name}.npz", weights=weights.astype(dtype))
    (tmp_path / "folder").mkdir()
    np.save(tmp_path / "plain.npy", np.zeros(12))
    (tmp_path / "plain.npy").rename(tmp_path / "plain.npz")
    return tmp_path


def _write(folder: Path, text: str) -> Path:
    path = folder / "player.yaml"
    path.write_text(text)
    return path


@pytest.mark.parametrize(("text", "names"), [b[1:] for b in BAD], ids=[b[0] for b in BAD])
def test_a_bad_player_file_is_one_value_error_naming_the_key(
    folder: Path, env: gym.Env, text: str, names: str
) -> None:
    path = _write(folder, text)
    with pytest.raises(ValueError, match=re.escape(names)) as caught:
        load_search_player(path, env)
    message = str(caught.value)
    assert message.startswith(f"player file {str(path)!r}: ")
    assert "\n" not in message  # one line: the commands print it as a usage error


def test_a_misspelt_key_suggests_the_right_one(folder: Path, env: gym.Env) -> None:
    path = _write(folder, GOOD + "setvalue: set_value.npz\n")
    with pytest.raises(ValueError, match=r"setvalue \(did you mean set_value\?\)"):
        read_player_file(path, env.unwrapped.config.table)


def test_a_missing_model_shows_where_it_was_looked_for(folder: Path, env: gym.Env) -> None:
    path = _write(folder, _swap("layout_value", GONE))
    # The written path, and the one looked at: under the file's folder, nothing else tried.
    looked = f"'{GONE}' not found (looked for {folder / GONE}:"
    with pytest.raises(ValueError, match=re.escape(looked)):
        read_player_file(path, env.unwrapped.config.table)


def test_a_missing_player_file_is_a_value_error(tmp_path: Path, env: gym.Env) -> None:
    with pytest.raises(ValueError, match=r"player file 'nothere\.yaml': not found \(looked for"):
        load_search_player("nothere.yaml", env)


def test_a_directory_as_the_player_file_is_a_value_error(folder: Path, env: gym.Env) -> None:
    with pytest.raises(ValueError, match=r"': is a directory, not a file \("):
        load_search_player(folder, env)


def test_a_duel_needs_the_duel_value(folder: Path, env: gym.Env) -> None:
    path = _write(folder, _swap("duel_value", None))
    assert load_search_player(path, env).objective == "runout"  # a run-out does not
    with pytest.raises(ValueError, match="duel_value is required to play an opponent"):
        load_search_player(path, env, players=2)


def test_a_good_file_loads_its_models_from_its_folder_whatever_the_directory(
    folder: Path, env: gym.Env, monkeypatch: pytest.MonkeyPatch
) -> None:
    (folder / "players").mkdir()
    moved = GOOD.replace(": runout_value", ": ../runout_value").replace(
        ": duel_value", f": {folder}/duel_value"
    )  # a relative path from the file's folder, and an absolute one
    path = folder / "players" / "player.yaml"
    path.write_text(moved.replace(": set_value", ": ../set_value"))
    monkeypatch.chdir(folder / "players")  # neither the repository nor the file's parent
    player = load_search_player(path.relative_to(folder / "players"), env)
    expected = LayoutValue.load(MODELS / "runout_value.npz").weights
    np.testing.assert_array_equal(player.layout_value.weights, expected)
    assert player.settings == SearchSettings(budget=0.5, samples=4)
    assert isinstance(player.leaf, SetLeaf)
    duel = load_search_player(path.relative_to(folder / "players"), env, players=2)
    expected = LayoutValue.load(MODELS / "duel_value.npz").weights
    np.testing.assert_array_equal(duel.layout_value.weights, expected)


@pytest.mark.parametrize(
    ("loader", "name", "message"),
    [
        (LayoutValue.load, "corrupt.npz", "is not an .npz archive of named arrays (not a zip"),
        (LayoutValue.load, "noweights.npz", "has no arrays ['weights']"),
        (LayoutValue.load, "plain.npz", "(a single .npy array)"),
        (SetValue.load, "truncated.npz", "is not a readable .npz archive"),
        (SetValue.load, "runout_value.npz", "has no arrays ['phi0_w'"),
    ],
)
def test_the_model_loaders_name_the_file(folder: Path, loader, name: str, message: str) -> None:
    with pytest.raises(ValueError, match=re.escape(f"{folder / name} ")) as caught:
        loader(folder / name)
    assert message in str(caught.value)


#: The committed files' first shots (break, then two) on fixed racks, recorded on the code
#: before the schema (commit b191a73) with the budget cut to nothing (and fans 0, as the files
#: were before issue 46), so that the second ply plays its one round whatever the machine's
#: speed: (file, players, seed) -> actions.
SHOTS = {
    ("search_player.yaml", None, 3): [
        [0.0, 0.0, 1.0, 0.2473513, 0.0, -1.0, 0.0, 0.1713692],
        [-0.3, -0.0864198, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0],
        [0.8742816, 0.1911247, 0.0, 0.0, 0.8333333, -1.0, 0.0, 1.0],
    ],
    ("search_player_net.yaml", None, 4): [
        [0.0, 0.0, 1.0, 0.2473513, 0.0, -1.0, 0.0, 0.1713692],
        [0.7123788, -0.0832274, 0.0, 0.0, 0.1666667, -1.0, -0.6, -0.5],
        [0.85, -0.0864198, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0],
    ],
    ("search_player.yaml", 2, 5): [
        [0.0, 0.0, 1.0, 0.2473513, 0.0, -1.0, 0.0, 0.1713692],
        [0.3, -0.7777778, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0],
        [0.0, -0.7777778, -0.6838519, 0.7055596, 0.0, -1.0, 0.0, 0.0],
    ],
}


@pytest.mark.parametrize(("name", "players", "seed"), list(SHOTS), ids=str)
def test_the_committed_files_play_the_shots_they_played_before(name, players, seed) -> None:
    env = gym.make(ENV_ID, noise="fastfiz")
    agent = make_agent(str(MODELS / name), env, players=players)
    assert agent.settings.budget == 1.0 and agent.settings.break_tip == (0.0, 0.25)
    assert isinstance(agent.leaf, SetLeaf) == (name == "search_player_net.yaml" and not players)
    assert agent.settings.fans == 8  # issue 46: the pots re-aimed (tests/agents/test_shot_fans.py)
    agent.settings = replace(agent.settings, budget=1e-9, fans=0)  # the shots recorded then
    obs, _ = env.reset(seed=seed)
    for expected in SHOTS[(name, players, seed)]:
        action, _ = agent.predict(obs)
        np.testing.assert_allclose(action, expected, rtol=0.0, atol=1e-6)
        obs, *_ = env.step(action)


def _usage_error(main, argv: list[str], capsys: pytest.CaptureFixture[str]) -> str:
    """The one error line a command prints when it exits with a usage error (status 2)."""
    with pytest.raises(SystemExit) as caught:
        main(argv)
    assert caught.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err[0].startswith("usage:") and "Traceback" not in "\n".join(err)
    return err[-1]


def test_the_commands_turn_a_bad_player_file_into_a_usage_error(
    folder: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    bad = str(_write(folder, _settings("budget: .inf")))
    commands = [
        (evaluate_main, ["--env", ENV_ID, "--agent", "ghost", bad, "--episodes", "1"]),
        (duels_main, ["--agent", "ghost", "--opponent", bad, "--racks", "1"]),
        (runouts_main, ["--agents", bad, "--racks", "1"]),
    ]
    for main, argv in commands:
        line = _usage_error(main, argv, capsys)
        assert "error: player file" in line and "settings.budget must be a finite" in line


@pytest.mark.parametrize(
    ("line", "says"),
    [
        ("samples: 1000000000000", "settings.samples must be an integer in [1, 512]"),
        ("samples: 2\n  samples: 3", "duplicate key settings.samples (lines 7 and 8)"),
    ],
)
def test_a_huge_count_or_a_key_twice_is_a_usage_error_before_playing(
    folder: Path, capsys: pytest.CaptureFixture[str], line: str, says: str
) -> None:
    bad = str(_write(folder, _settings(line)))
    line = _usage_error(evaluate_main, ["--env", ENV_ID, "--agent", bad, "--episodes", "1"], capsys)
    assert f"error: player file {bad!r}: {says}" in line


def test_a_good_player_file_passes_the_commands_check(folder: Path) -> None:
    parser = argparse.ArgumentParser()
    good = str(_write(folder, GOOD))
    check_agents(parser, ["ghost", good], ENV_ID, None)  # no exit
    check_agents(parser, [good], ENV_ID, {"noise": "fastfiz"}, players=2)
    upper = folder / "PLAYER.YML"  # a player file whatever the suffix's case
    upper.write_text(GOOD)
    check_agents(parser, [str(upper), "const:0,1,0,0,0,0,0,0"], ENV_ID, None)
    env = gym.make(ENV_ID)
    assert make_agent(str(upper), env).settings == SearchSettings(budget=0.5, samples=4)


#: (id, the agent as written, what the error line must say beside it).
BAD_AGENTS = [
    ("a missing .yml", "gone.yml", "a search player file not found"),
    ("a missing .YAML", "GONE.YAML", "a search player file not found"),
    ("a missing .zip", "gone.zip", "an SB3 model not found"),
    ("a missing .npz", "gone.npz", "a rack, lookahead or rack-network model not found"),
    ("a directory", "{folder}", "is a directory, not a file"),
    ("a directory with a model's suffix", "{folder}/folder.npz", "is a directory, not a file"),
    ("a misspelt name", "gohst", "(did you mean ghost?): an agent is one of random, const,"),
    ("an unknown suffix", "model.pt", "or a file (any case): an SB3 model .zip, a rack, "
     "lookahead or rack-network model .npz, a search player file .yaml/.yml"),
    ("a const of letters", "const:a,b", "takes the env's 8 action numbers, each in [-1, 1]"),
    ("a const out of range", "const:0,2,0,0,0,0,0,0", "takes the env's 8 action numbers"),
]  # fmt: skip


@pytest.mark.parametrize(
    ("agent", "says"), [b[1:] for b in BAD_AGENTS], ids=[b[0] for b in BAD_AGENTS]
)
def test_the_commands_turn_a_bad_agent_into_a_usage_error(
    folder: Path, capsys: pytest.CaptureFixture[str], agent: str, says: str
) -> None:
    (folder / "folder.npz").mkdir()
    agent = agent.format(folder=folder)
    commands = [
        (evaluate_main, ["--env", ENV_ID, "--agent", "ghost", agent, "--episodes", "1"]),
        (duels_main, ["--agent", agent, "--opponent", "ghost", "--racks", "1"]),
        (duels_main, ["--agent", "ghost", "--opponent", "random", agent, "--racks", "1"]),
        (runouts_main, ["--agents", "ghost", agent, "--racks", "1"]),
    ]
    for main, argv in commands:
        line = _usage_error(main, argv, capsys)
        assert f"agent {agent!r}" in line and says in line
