"""What learns or was learned: the envs a learner sees, loaded models, the 9-ball players.

``envs`` (``gym.make`` plus an observation wrapper by name), ``features`` (pocket and
ghost-ball features), ``candidates`` (the action as a score per candidate shot);
``pretrained`` (:func:`agents.load`: a saved SB3 model with its observation wrapper); and
the 9-ball players on the spin ids: ``rack_play`` (``RackAgent``, a learned value over the
planner's candidate pots), ``lookahead`` (``LookaheadAgent``: candidates played out on the
game's own step, ``game_model``, and valued by a learned layout value, ``layout_value``).
"""
