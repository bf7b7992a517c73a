"""The families of steps of the workflow, one module each: every family declares its steps
(``steps(ctx)``: one :class:`~hubbeam.pipeline.steps.Step` per rule, by rule name), the files of
``all`` it builds and the archive bundles (``targets(ctx)``) and, optionally, target rules of its
own (``target_rules(ctx)``: rule name -> its files, or a function giving them when the rule runs).
Every family reads the checked configuration through :class:`hubbeam.pipeline.context.PlanContext`
and no other family. A new family is a new module here and its line in :data:`FAMILIES`."""

from hubbeam.pipeline.families import (
                                       control,
                                       eigen,
                                       figures,
                                       identification,
                                       linear,
                                       paper,
                                       plants,
                                       reports,
                                       simulations,
                                       sweeps,
                                       validation,
)

#: every family of steps, in the order their targets are listed
FAMILIES = (simulations, eigen, linear, plants, control, figures, paper, reports, sweeps, validation,
            identification)
