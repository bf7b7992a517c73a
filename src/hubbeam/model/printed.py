"""Numbers printed in Bai et al. 2009 (the journal version), for comparison only.

Nothing in the model reads these values: they are what tables, tests of the input data and the
reproduction report set our computed results against. Table 2's caption is swapped with Table 3's
in the journal (reproduction note 3): the values below are the first five vibration
frequencies, in Hz; TLAM and FOAM at a constant hub speed of 1 rad/s.
"""

#: Table 1, physical parameters (SI), keyed like :class:`hubbeam.model.parameters.BeamParameters`.
TABLE1 = {
    "L": 8.0,  # m
    "rho": 2.7667e3,  # kg m-3
    "A": 7.2968e-5,  # m2
    "E": 6.8952e10,  # N m-2
    "I": 8.2189e-9,  # m4
    "Jh": 200.0,  # kg m2
    "rA": 0.5,  # m
}
#: Table 1, tip mass (kg).
TABLE1_TIP_MASS = 0.1

#: Table 2, hub speed of the TLAM and FOAM rows (rad s-1).
TABLE2_SPEED = 1.0
#: Table 2, first five frequencies (Hz) per row.
TABLE2 = {
    "natural": (0.4635, 2.9047, 8.1332, 15.9377, 26.3462),
    "TLAM": (0.4353, 2.9003, 8.1316, 15.9369, 26.3457),
    "FOAM": (0.4714, 2.9308, 8.1618, 15.9682, 26.3776),
}

#: Section 4.2 and 4.4: TLAM critical angular velocity (rad s-1) for a tip mass (kg) at the
#: beam tip, keyed by mass; 0.0 is the bare beam (the text also quotes it for m_t on the hub).
CRITICAL_SPEEDS_TLAM = {0.0: 2.91, 0.1: 2.60, 0.5: 1.91}

# --- Section 4 statements checked by the reproduction report (hubbeam.paper.report) -------------------

#: Table 3 (printed under Table 2's caption, note 3): largest |Q_theta| (N m) per tau_max (N m).
#: As printed, not monotonic in tau_max (note 9).
TABLE3 = {50.0: 6.24e-3, 100.0: 4.61e-2, 200.0: 3.72e-2, 400.0: 2.62}
#: Section 4.3: "about 6.5 %" of tau_max = 400 N m (2.62 / 400 is 0.655 %, note 9).
Q_THETA_PERCENT_OF_TAU_MAX_400 = 6.5
#: Section 4.2, w_f = 2.8 rad/s: peak tip deflection (m) per model ("approximately").
PEAK_TIP_DEFLECTION_WF2P8 = {"TLAM": 0.49, "FOAM": 0.22}
#: Section 4.2, w_f = 2.8 rad/s: residual vibration amplitude TLAM / FOAM ("approximately 100").
RESIDUAL_RATIO_TLAM_FOAM_WF2P8 = 100.0
#: Section 4.3, FOAM, w_f = 5 rad/s, t_f = 30 s: peak transverse / peak axial tip response.
TRANSVERSE_AXIAL_PEAK_RATIO_WF5 = 1500.0
#: Section 4.3, tau_max = 200 N m: residual vibration of SFOAM against FOAM.
SFOAM_PHASE_LEAD_RAD_TAU200 = 0.45
SFOAM_AMPLITUDE_REDUCTION_PERCENT_TAU200 = 24.0
