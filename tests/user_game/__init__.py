"""A game written outside ``pool_env/``, in one folder: what ``docs/own_game.md`` builds."""
