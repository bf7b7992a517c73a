"""Published first frequencies of uniform rotating cantilevers, exactly as printed.

Dimensionless quantities (the sources' own):

* speed ratio       ``gamma = Omega sqrt(rho A L^4 / (E I))``
* frequency         ``omega_bar = omega sqrt(rho A L^4 / (E I))``
* slenderness       ``alpha = sqrt(A L^2 / I)`` (enters only through the axial stiffness ``EA``)
* hub radius ratio  ``delta = rA / L``
* tip-mass ratio    ``mu = m_t / (rho A L)``

Values are kept as the printed text, so that the number of printed decimals (and with it the
precision the source claims) is not lost; :func:`printed_unit` gives one unit in the last printed
place. The values are transcribed from the tables of the sources below.

Sources
-------
``wright1982``
    A. D. Wright, C. E. Smith, R. W. Thresher, J. L. C. Wang: Vibration modes of centrifugally
    stiffened beams. Journal of Applied Mechanics 49 (1982) 197-202 (Frobenius series solution).
``hodges1981``
    D. H. Hodges, M. J. Rutkowski: Free-vibration analysis of rotating beams by a variable-order
    finite-element method. AIAA Journal 19 (1981) 1459-1466.
    The classic flapwise row (``delta = 0``, ``gamma = 0..12``) is the one both papers tabulate.
``hamza-cherif2004``
    S. M. Hamza-Cherif, A. Houmat: Natural frequencies of rotating cantilever flexible beams by
    using the p-version of the finite element method. 24th International Congress of the
    Aeronautical Sciences (ICAS 2004), Table 2 (``delta = 0``, ``alpha = 70``): flapwise and
    chordwise first frequencies, the chordwise ones with the axial stretch and the Coriolis
    coupling of axial and chordwise motion included.
``tip-mass-frequency-equation``
    Non-rotating cantilever with a point mass at its free end: the roots ``b = beta L`` of
    ``1 + cos b cosh b + mu b (cos b sinh b - sin b cosh b) = 0``, ``omega = b^2 sqrt(EI /
    (rho A L^4))``, as tabulated in the reference file (a classical result; no single paper).

How the last printed digit was obtained is not stated by the sources; docs/validation.md gives
the evidence for our reading (``ROUNDING``) and :mod:`hubbeam.validation.rotating_eigen` the
tolerances that follow from it.
"""

from __future__ import annotations

from decimal import Decimal
from typing import NamedTuple

CITATIONS = {
    "wright1982": (
        "A. D. Wright, C. E. Smith, R. W. Thresher, J. L. C. Wang: Vibration modes of "
        "centrifugally stiffened beams. Journal of Applied Mechanics 49 (1982) 197-202."
    ),
    "hodges1981": (
        "D. H. Hodges, M. J. Rutkowski: Free-vibration analysis of rotating beams by a "
        "variable-order finite-element method. AIAA Journal 19 (1981) 1459-1466."
    ),
    "hamza-cherif2004": (
        "S. M. Hamza-Cherif, A. Houmat: Natural frequencies of rotating cantilever flexible beams "
        "by using the p-version of the finite element method. ICAS 2004 (24th International "
        "Congress of the Aeronautical Sciences), Table 2."
    ),
    "tip-mass-frequency-equation": (
        "Frequency equation of a uniform Euler-Bernoulli cantilever with a point mass at its free "
        "end, 1 + cos b cosh b + mu b (cos b sinh b - sin b cosh b) = 0 (classical)."
    ),
}

#: Author-year names of the sources for tables, legends and report text.
SHORT_NAMES = {
    "wright1982": "Wright et al. (1982)",
    "hodges1981": "Hodges and Rutkowski (1981)",
    "hamza-cherif2004": "Hamza-Cherif and Houmat (2004)",
    "tip-mass-frequency-equation": "tip-mass frequency equation",
}


def short_name(source: str) -> str:
    """Author-year name of ``source``, a key of :data:`CITATIONS` or several joined by ``+``."""
    keys = source.split("+")
    unknown = [key for key in keys if key not in SHORT_NAMES]
    if unknown:
        raise KeyError(f"source {source!r}: unknown key(s) {unknown}; allowed: {sorted(SHORT_NAMES)}")
    return "; ".join(SHORT_NAMES[key] for key in keys)


#: How the last printed digit of each table was obtained, as we read it (evidence in
#: docs/validation.md): "rounded" (to nearest) or "truncated" (chopped towards zero).
ROUNDING = {
    "wright1982+hodges1981": "rounded",
    "hamza-cherif2004": "truncated",
    "tip-mass-frequency-equation": "rounded",
}


class RotatingValue(NamedTuple):
    """One published first frequency ``omega_bar_1`` of a rotating uniform cantilever."""

    source: str  # key of CITATIONS (several joined by '+')
    direction: str  # "flapwise" (out of the plane of rotation) or "chordwise" (in the plane)
    gamma: float  # dimensionless speed
    alpha: float | None  # slenderness; None where it does not enter (flapwise)
    delta: float  # hub radius ratio
    printed: str  # the value as printed

    @property
    def value(self) -> float:
        return float(self.printed)


class TipMassRoot(NamedTuple):
    """First root ``beta_1 L`` of the non-rotating cantilever with tip-mass ratio ``mu``."""

    mu: float
    printed: str

    @property
    def value(self) -> float:
        return float(self.printed)


def printed_unit(text: str) -> float:
    """One unit in the last printed decimal place of ``text`` (``"4.97"`` -> 0.01)."""
    exponent = Decimal(text.strip()).as_tuple().exponent
    if not isinstance(exponent, int):
        raise ValueError(f"printed value {text!r}: expected a finite decimal number")
    return float(Decimal(1).scaleb(exponent))


_CLASSIC_FLAPWISE = ("3.5160", "3.6816", "4.1373", "4.7973", "5.5850", "6.4495", "7.3604",
                     "8.2996", "9.2568", "10.2257", "11.2023", "12.1843", "13.1702")

_HC_GAMMA = (2.0, 4.0, 6.0, 8.0, 10.0, 50.0)
_HC_FLAPWISE = ("4.1373", "5.5850", "7.3603", "9.2568", "11.2023", "51.0805")
_HC_CHORDWISE = ("3.6195", "3.888", "4.2393", "4.6105", "4.97", "7.3362")

#: Every published rotating first frequency, in table order.
ROTATING_FIRST_FREQUENCIES = (
    tuple(RotatingValue("wright1982+hodges1981", "flapwise", float(g), None, 0.0, text)
          for g, text in enumerate(_CLASSIC_FLAPWISE))
    + tuple(RotatingValue("hamza-cherif2004", "flapwise", g, 70.0, 0.0, text)
            for g, text in zip(_HC_GAMMA, _HC_FLAPWISE))
    + tuple(RotatingValue("hamza-cherif2004", "chordwise", g, 70.0, 0.0, text)
            for g, text in zip(_HC_GAMMA, _HC_CHORDWISE))
)

#: First roots beta_1 L of the cantilever with a tip mass (non-rotating).
TIP_MASS_ROOTS = (
    TipMassRoot(0.0, "1.87510"),
    TipMassRoot(0.1, "1.72274"),
    TipMassRoot(0.2, "1.61640"),
    TipMassRoot(0.5, "1.41996"),
    TipMassRoot(1.0, "1.24792"),
    TipMassRoot(2.0, "1.07620"),
)
