"""The spin level (pooltool's model) as a strategy of the one event loop: see :mod:`.level`."""
