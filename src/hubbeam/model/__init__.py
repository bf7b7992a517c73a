"""The rotating beam as the paper models it: the model table (TLAM, FOAM, SFOAM, CFOAM), the
physical parameters, the beam's assumed modes and their quadrature, the system matrices and their
linearisation, the eigenvalue problems (critical speeds, natural frequencies), damping, the hub
maneuvers and the shapers of their commands, where each model is valid, the bounds of the
numerical settings and the values the paper prints (what the model is compared with)."""
