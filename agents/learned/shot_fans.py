"""Aim each planned pot at the middle of its pot window, found on the noiseless model.

A planner's pot (the spin planner's exact contact, the ghost-ball agent's choice) aims where
its closed forms say the object ball drops. The model it is played on (the game's own step:
throw, squirt, the cloth) moves the window of aims that pot, and the planned aim can sit
near one edge of it: under the execution noise half of the shots then fall out of the
window on that side. :class:`AimWindows` plays a fan of aims around each pot's aim, once
each on the game's step *without* noise (:data:`FAN_STEP` apart, ``steps`` either side),
marks the aims that pot and keep the table (or win the rack), and re-aims the pot at the
middle of the run of such aims that holds the planned aim, or the nearest run when the
planned aim misses. For an aim error that is symmetric and unimodal (the noise is
Gaussian) the middle of a window is the aim that pots most often: it is the shot chosen by
its success under the noise, without the sampling error of a few noisy plays per aim.

The run is cut at the fan's ends, so a window wider than the fan is centred on the part
the fan sees (a shift towards the planned aim: still inside the window).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from agents.learned.game_model import GameModel
from pool_env.game.codec import encode_shots
from pool_env.game.config import GameConfig, make_config
from pool_env.game.formulas import decode_on_layout
from pool_env.game.games.wpa.judge import FOUL, KEEPS, WINNER

#: The fan's spacing (rad): half of FastFiz's aim sigma (0.125 deg), so that a window a
#: sigma wide holds two or three aims of the fan.
FAN_STEP = 0.5 * np.deg2rad(0.125)


def window_centres(success: NDArray[np.bool_]) -> NDArray[np.float64]:
    """``(C,)`` each fan's re-aim, in fan steps from its middle (0: keep the planned aim).

    Args:
        success: ``(C, F)`` whether aim ``f`` of fan ``c`` pots (``F`` odd, the planned aim
            in the middle).

    Returns:
        The middle of the run of successes that holds the planned aim; with the planned
        aim a failure, of the run nearest to it (the left one on a tie); 0 for a fan
        without success.
    """
    ok = np.asarray(success, dtype=np.bool_)
    c, f = ok.shape
    middle = f // 2
    out = np.zeros(c)
    for row in range(c):
        hits = np.flatnonzero(ok[row])
        if not hits.size:
            continue
        start = int(hits[np.argmin(np.abs(hits - middle))])  # argmin: the left one on a tie
        lo = hi = start
        while lo > 0 and ok[row, lo - 1]:
            lo -= 1
        while hi < f - 1 and ok[row, hi + 1]:
            hi += 1
        out[row] = 0.5 * (lo + hi) - middle
    return out


class AimWindows:
    """Re-aims candidate shots at the middle of their pot windows (module doc).

    Args:
        config: The env's config (its noise is dropped for the fans).
        steps: Aims tried either side of the planned one, :data:`FAN_STEP` apart.
    """

    def __init__(self, config: GameConfig, steps: int) -> None:
        if steps < 1:
            raise ValueError(f"steps must be >= 1, got {steps}")
        self.config = config
        self.steps = steps
        exact = make_config(config.source, players=config.players, noise=None)
        self.model = GameModel(exact, 0)

    def centre(
        self,
        positions: NDArray[np.float64],
        on: NDArray[np.bool_],
        reference: NDArray[np.bool_],
        rack: NDArray[np.int64],
        actions: NDArray[np.float64],
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The actions re-aimed, and each one's shift (rad).

        Args:
            positions: ``(N, 2)`` ball centres, the cue ball placed.
            on: ``(N,)`` the balls on the table.
            reference: ``(N,)`` the balls the aim may refer to (the legal first balls).
            rack: ``(N_RACK,)`` the rack state shot from (no ball in hand).
            actions: ``(C, A)`` full env actions.

        Returns:
            ``(actions, shifts)``: ``(C, A)`` copies, the aim column moved (the other
            columns as given), and ``(C,)`` the moves in radians (0 where the fan found
            no pot, or an aim the aim mode cannot play).
        """
        acts = np.array(actions, dtype=np.float64)
        c = acts.shape[0]
        if not c:
            return acts, np.zeros(0)
        angles, speeds = decode_on_layout(self.config, acts, positions, reference)
        offsets = np.arange(-self.steps, self.steps + 1) * FAN_STEP
        f = offsets.size
        fan_angles = (angles[:, None] + offsets[None]).reshape(1, -1)
        fan_speeds = np.repeat(speeds, f).reshape(1, -1)
        parts, playable = encode_shots(
            self.config, positions[None], reference[None], fan_angles, fan_speeds
        )
        fans = np.repeat(acts, f, axis=0)
        fans[:, 0] = parts[0, :, 0]
        result, _, _ = self.model.play(positions, on, rack, fans, 1)
        hits = result.hits
        potted = (hits[:, WINNER] == 0) | ((hits[:, FOUL] == 0) & (hits[:, KEEPS] != 0))
        success = (potted & playable[0]).reshape(c, f)
        steps = window_centres(success)
        shifts = steps * FAN_STEP
        moved = np.flatnonzero(steps != 0.0)
        if moved.size:  # re-encoded: a run of even length has its middle between two aims
            again, ok = encode_shots(
                self.config, positions[None], reference[None],
                (angles[moved] + shifts[moved])[None], speeds[moved][None],
            )  # fmt: skip
            acts[moved, 0] = np.where(ok[0], again[0, :, 0], acts[moved, 0])
            shifts[moved] = np.where(ok[0], shifts[moved], 0.0)
        return acts, shifts
