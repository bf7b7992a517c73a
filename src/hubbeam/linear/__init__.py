"""Linear models of the hub-beam about a steady spin: state space, its two routes, its export."""

from hubbeam.linear.statespace import HUBS, OUTPUTS, LinearModel, linear_model, plant

__all__ = ["HUBS", "OUTPUTS", "LinearModel", "linear_model", "plant"]
