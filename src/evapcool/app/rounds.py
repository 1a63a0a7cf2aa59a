"""Making and restarting games: the settings a new game takes, and the parts it resets.

A restart takes the class challenge's settings and seed if one is on, a watched
recording's if one is watched, else the saved settings with this run's overrides; the
recording, the name box, the autopilot and the charts start over with it. Where the
keyboard goes afterwards is the input machine's own business (it resets itself).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

from evapcool.app.charts import ChartColumn
from evapcool.app.classmode import ClassMode
from evapcool.app.notices import Notices
from evapcool.app.options import SettingsEditor
from evapcool.app.pilot import PilotSeat
from evapcool.app.replays import ReplayKeeper
from evapcool.app.scoring import Scoreboard
from evapcool.app.words import t
from evapcool.game.replay import Recording
from evapcool.game.replay import Settings as RecordedSettings
from evapcool.game.rules import HEIGHT_START, Game, GameConfig
from evapcool.game.settings import Settings
from evapcool.physics.simulation import Simulation


class Rounds:
    """The game in play, and each new one: for the next student, or with new settings."""

    def __init__(
        self,
        game: Game,
        build: Callable[[GameConfig], Simulation],
        *,
        options: SettingsEditor,
        scores: Scoreboard,
        replays: ReplayKeeper,
        pilot: PilotSeat,
        classroom: ClassMode,
        charts: ChartColumn,
        notices: Notices,
        watching: Recording | None = None,
    ) -> None:
        """build: a new simulation for a config; watching: a recording watched (`--replay`),
        its heights frame by frame in every game."""
        self.game = game
        self.build = build
        self.options = options
        self.scores = scores
        self.replays = replays
        self.pilot = pilot
        self.classroom = classroom
        self.charts = charts
        self.notices = notices
        self.watching = watching
        replays.attach(game)  # every game is recorded, the autopilot's too
        if watching is not None:
            game.playback(watching.moves)
            notices.news(t("desk.replay.watching", edition=watching.edition))

    def _config(self) -> GameConfig:
        """The next game's config: the class's, the recording's, or the settings'."""
        challenge, watching = self.classroom.challenge, self.watching
        s: Settings | RecordedSettings
        if watching is not None:
            s = watching.settings
        else:
            s = challenge.settings if challenge else self.options.for_run()
        config = replace(
            self.game.config,
            n_atoms=s.n_atoms,
            radius=s.radius,
            tc_exponent=s.tc_exponent,
            escape=s.escape,
        )
        if challenge is not None:  # everyone in the class plays the same atoms
            config = replace(config, seed=challenge.seed, start_height=HEIGHT_START)
        if watching is not None:
            config = replace(config, seed=watching.seed, start_height=HEIGHT_START)
        return config

    def restart(self) -> None:
        """New atoms with the current settings, trap at 400, paused; ends any name entry."""
        config = self._config()
        self.notices.new_game()  # the last game's news is over
        try:
            self.game.restart(config, sim=self.build(config))
        except ValueError as exc:  # settings are validated; this is a guard, not a path
            self.notices.problem(t("notice.settings_failed", problem=exc))
            self.game.restart()
        self.replays.start(self.game)
        if self.watching is not None:
            self.game.playback(self.watching.moves)
        self.scores.new_round()
        self.pilot.new_game(self.game)
        self.charts.reset()

    def next_player(self) -> bool:
        """Enter after a stored (or skipped) score: a fresh game for the next student."""
        if not self.scores.ready_for_next:
            return False
        self.restart()
        return True
