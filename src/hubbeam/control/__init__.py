"""Control design on the linear models: state and output feedback on the hub, gains given or
designed by LQR on one model and run on another in the nonlinear simulation (docs/control.md);
command shapers tuned on the mode a maneuver's command excites (docs/command-shaping.md)."""
