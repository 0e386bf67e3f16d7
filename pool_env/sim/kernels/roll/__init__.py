"""The roll level (the seed's model) as a strategy of the one event loop: see :mod:`.level`."""
