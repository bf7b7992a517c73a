"""The error of a run that cannot be made as asked (the message names the argument or key, the
value and what is allowed)."""


class SimulationError(ValueError):
    """A case, its numerics or its controller cannot be simulated; the message names key, value and
    allowed."""
