# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The receptors of a feed: their polarization and their angle in the antenna.

A dual-polarization feed has two receptors: right- and left-hand circular
(``R``, ``L``) or two linear dipoles (``X``, ``Y``). Visibility files give
each receptor an angle in the antenna: ``POLAA``/``POLAB`` in the antenna
tables of FITS-IDI and UVFITS files, ``RECEPTOR_ANGLE`` in the ``FEED``
table of a Measurement Set, ``feed_angle`` in pyuvdata. Seen on the sky, a
receptor then lies at the position angle

.. math:: \\theta = \\Phi + \\alpha,

where :math:`\\Phi` is the feed rotation of the antenna
(`~astropy_feedrot.Antenna.feed_rotation`, the position angle of the
receiver's reference direction, north through east) and :math:`\\alpha` the
receptor angle. For an alt-az Cassegrain antenna :math:`\\Phi` is the
parallactic angle, so :math:`\\alpha = 0` is a dipole along the vertical
(toward the zenith) and :math:`\\alpha = 90^\\circ` a horizontal one, as in
the AIPS and pyuvdata conventions.

A receptor at position angle :math:`\\theta` answers to the field on the sky
(components toward north and east) with the row

* linear: :math:`(\\cos\\theta, \\sin\\theta)`;
* circular (IEEE right-handed, IAU): :math:`e^{-i\\theta}(1, i)/\\sqrt{2}`
  for R and :math:`e^{+i\\theta}(1, -i)/\\sqrt{2}` for L,

so that a feed rotated by :math:`\\Phi` multiplies its RCP voltage by
:math:`e^{-i\\Phi}` and its LCP voltage by :math:`e^{+i\\Phi}`, the
convention of `~astropy_feedrot.applied.correction` (Appendix D of the paper).

The two receptors of a circular feed turn together: both lie at the angle of
the *first* receptor of the file (``POLAA``, ``RECEPTOR_ANGLE[0]``, pyuvdata's
first ``feed_angle``), whatever angle the file gives the second
(`Receptors.sky_angles`). This is CASA's rule (its parallactic-angle
correction turns both hands by the first receptor's angle; checked with
casatools' ``applycal(parang=True)`` on ``RECEPTOR_ANGLE`` [20, 110] and [20,
50] deg: RL moves by 40 deg in both) and AIPS's, whose files give both the same
angle. Files write the second angle equal to the first (AIPS, DiFX, SFXC,
casacore) or 90 deg on (HOPS, pyuvdata): `CIRCULAR_OFFSETS`. Any other
offset is unusual (`Receptors.unusual_offset`), and the correction warns.
"""

import numpy as np
from astropy import units as u
from astropy.coordinates import Angle
from astropy.utils.masked import Masked

__all__ = ["Receptors", "RECEPTOR_TYPES", "PRODUCT_CODES", "basis_of", "CIRCULAR_OFFSETS"]

#: The receptor types, by basis.
RECEPTOR_TYPES = {"circular": ("R", "L"), "linear": ("X", "Y")}

#: The codes of the correlation products in the ``STOKES`` axis of FITS-IDI
#: and UVFITS files and in pyuvdata's ``polarization_array`` (AIPS Memo 117);
#: the first letter is the receptor of antenna 1.
PRODUCT_CODES = {-1: "RR", -2: "LL", -3: "RL", -4: "LR",
                 -5: "XX", -6: "YY", -7: "XY", -8: "YX"}

#: The angles (deg, modulo 360) by which files put the second receptor of a circular
#: feed from the first without meaning anything by it: the same angle (AIPS, DiFX,
#: SFXC, casacore) or 90 deg on either side (HOPS and pyuvdata write R 0, L 90).
CIRCULAR_OFFSETS = (0.0, 90.0, 270.0)

# Two linear receptors closer than this to parallel (sine of the angle between
# them) cannot be told apart.
_MIN_SINE = 1e-6


def basis_of(types):
    """The basis, ``'circular'`` or ``'linear'``, of receptor or product letters.

    Parameters
    ----------
    types : str or sequence of str
        Receptor letters (``'R'``, ``'L'``, ``'X'``, ``'Y'``, any case), or
        correlation products such as ``'RL'`` whose letters are receptors.

    Returns
    -------
    str
        ``'circular'`` or ``'linear'``.

    Raises
    ------
    ValueError
        For an unknown letter, or letters of both bases (mixed circular and
        linear receptors are not supported).

    Examples
    --------
    >>> from astropy_feedrot.antennas.receptors import basis_of
    >>> basis_of("RL")
    'circular'
    >>> basis_of(["XX", "YY", "XY", "YX"])
    'linear'
    """
    letters = "".join(types if isinstance(types, str) else map(str, types)).upper()
    known = {letter: basis for basis, pair in RECEPTOR_TYPES.items() for letter in pair}
    unknown = sorted({letter for letter in letters if letter not in known})
    if unknown or not letters:
        raise ValueError(f"receptor types are R and L (circular) or X and Y (linear), got "
                         f"{types!r}")
    bases = {known[letter] for letter in letters}
    if len(bases) > 1:
        raise ValueError(
            f"{types!r} mixes circular (R, L) and linear (X, Y) receptors; a baseline "
            "between a linear and a circular feed is not supported (convert one of them "
            "first, e.g. with PolConvert)"
        )
    return bases.pop()


class Receptors:
    """The receptors of an antenna's feed: their types and angles.

    Parameters
    ----------
    types : str or sequence of str
        One or two receptor letters: ``'RL'``, ``'LR'``, ``'XY'``, ``'YX'``,
        ``'R'``, ``'X'``... (any case), in the order of the file.
    angles : `~astropy.units.Quantity` or `~astropy.coordinates.Angle`, optional
        The angle :math:`\\alpha` of each receptor in the antenna (module
        docstring), one per type. By default 0 for circular receptors, and
        0 for ``X`` and 90 deg for ``Y``.

    Raises
    ------
    TypeError
        If ``angles`` is a plain number or array instead of an angle.
    astropy.units.UnitsError
        If ``angles`` are not angles.
    ValueError
        For unknown, repeated or mixed types, more than two receptors, a
        number of angles that is not the number of types, non-finite or
        masked angles, or two linear receptors that are parallel.

    Examples
    --------
    pyuvdata's default for the Allen Telescope Array: ``x`` horizontal
    (90 deg) and ``y`` vertical (0 deg):

    >>> import astropy.units as u
    >>> from astropy_feedrot.antennas.receptors import Receptors
    >>> ata = Receptors("XY", [90, 0] * u.deg)
    >>> ata
    Receptors('XY', [90.0, 0.0] * u.deg)
    >>> ata.basis
    'linear'
    >>> ata.position_angles(30 * u.deg)  # doctest: +FLOAT_CMP
    <Angle [120., 30.] deg>
    """

    def __init__(self, types, angles=None):
        if isinstance(types, bytes):
            types = types.decode("ascii", "replace")
        if isinstance(types, str):
            letters = tuple(types.strip().upper())
        else:
            try:
                letters = tuple(str(t).strip().upper() for t in types)
            except TypeError:
                raise TypeError(f"types must be a string such as 'RL' or 'XY', got "
                                f"{type(types).__name__}") from None
        if not 1 <= len(letters) <= 2:
            raise ValueError(f"a feed has one or two receptors, got {len(letters)} types "
                             f"{types!r}")
        self.basis = basis_of(letters)
        if len(set(letters)) != len(letters):
            raise ValueError(f"receptor types {types!r} repeat a receptor")
        self.types = "".join(letters)
        if angles is None:
            angles = [90.0 if letter == "Y" else 0.0 for letter in letters] * u.deg
        if isinstance(angles, Masked):
            if np.any(angles.mask):
                raise ValueError(f"receptor angles must all be known, got masked values "
                                 f"{angles}; give the angle of every receptor")
            angles = angles.unmasked
        if not isinstance(angles, u.Quantity):
            raise TypeError(f"angles must be an angle Quantity (e.g. [0, 90] * u.deg), got "
                            f"{type(angles).__name__}")
        if angles.unit.physical_type != "angle":
            raise u.UnitsError(f"angles must be angles, got {angles.unit}")
        angles = Angle(np.atleast_1d(angles).astype(float), copy=True).to(u.deg)
        if angles.shape != (len(letters),):
            raise ValueError(f"give one angle per receptor: {len(letters)} types "
                             f"{self.types!r} but angles of shape {angles.shape}")
        if not np.all(np.isfinite(angles)):
            raise ValueError(f"receptor angles must be finite, got {angles}")
        if self.basis == "linear" and len(letters) == 2:
            sine = abs(np.sin((angles[1] - angles[0]).to_value(u.rad)))
            if sine < _MIN_SINE:
                raise ValueError(f"the linear receptors {self.types!r} are parallel "
                                 f"({angles[0]:.6g} and {angles[1]:.6g}); their signals "
                                 "cannot be separated")
        self.angles = angles

    @classmethod
    def from_text(cls, text, what="receptors"):
        """Receptors from a text: ``'R,L'``, ``'X,Y'`` or ``'X:45,Y:135'``.

        The form of ``feedrot correct --feeds`` and of the station
        catalogue's ``receptors`` column.

        Parameters
        ----------
        text : str
            Two receptor letters separated by a comma, each optionally
            followed by ``:angle`` in degrees (default 0 for R, L and X, 90
            for Y).
        what : str, optional
            What the text is, for error messages.

        Returns
        -------
        `Receptors`

        Raises
        ------
        ValueError
            For anything else, with the accepted forms.

        Examples
        --------
        >>> from astropy_feedrot.antennas.receptors import Receptors
        >>> Receptors.from_text("X:45,Y:135")
        Receptors('XY', [45.0, 135.0] * u.deg)
        >>> Receptors.from_text("R,L").types
        'RL'
        """
        usage = ("give two letters with optional angles in degrees, e.g. 'R,L', 'X,Y' or "
                 "'X:45,Y:135'")
        parts = [p.strip() for p in str(text).split(",")]
        if len(parts) != 2:
            raise ValueError(f"{what} {text!r}: {usage}")
        types, angles = "", []
        for part in parts:
            letter, _, angle = part.partition(":")
            letter = letter.strip().upper()
            if letter not in ("R", "L", "X", "Y"):
                raise ValueError(f"{what} {text!r}: unknown receptor {letter!r}; {usage}")
            try:
                value = float(angle) if angle.strip() else (90.0 if letter == "Y" else 0.0)
            except ValueError:
                raise ValueError(f"{what} {text!r}: angle {angle!r} is not a number; "
                                 f"{usage}") from None
            types += letter
            angles.append(value)
        return cls(types, angles * u.deg)

    @classmethod
    def paired(cls, receptor, angle=None):
        """The two receptors of a feed of which a file names one.

        Files of single-polarization data often name one receptor: a blank
        ``POLTYB`` (casacore's UVFITS), ``'?'`` (SFXC's FITS-IDI, the
        ``POLARIZATION_TYPE`` of the Measurement Sets CASA imports from
        them). The second receptor is the other of the basis, at the same
        angle (circular) or 90 deg further (linear: ``Y`` at ``X + 90``
        deg), in the order of the file: the named receptor first.

        Parameters
        ----------
        receptor : str
            ``'R'``, ``'L'``, ``'X'`` or ``'Y'`` (any case).
        angle : `~astropy.units.Quantity`, optional
            Its angle in the antenna (default 0 for R, L and X, 90 deg for Y).

        Returns
        -------
        `Receptors`

        Raises
        ------
        ValueError
            For any other letter.

        Examples
        --------
        >>> import astropy.units as u
        >>> from astropy_feedrot.antennas.receptors import Receptors
        >>> Receptors.paired("l", 10 * u.deg)
        Receptors('LR', [10.0, 10.0] * u.deg)
        >>> Receptors.paired("Y", 0 * u.deg)
        Receptors('YX', [0.0, -90.0] * u.deg)
        """
        letter = str(receptor).strip().upper()
        if len(letter) != 1:
            raise ValueError(f"give one receptor letter (R, L, X or Y), got {receptor!r}")
        basis = basis_of(letter)
        if angle is None:
            angle = (90.0 if letter == "Y" else 0.0) * u.deg
        angle = u.Quantity(angle, u.deg).ravel()[0]
        other = [t for t in RECEPTOR_TYPES[basis] if t != letter][0]
        step = 0.0 if basis == "circular" else (90.0 if letter == "X" else -90.0)
        return cls(letter + other, u.Quantity([angle, angle + step * u.deg]))

    def __repr__(self):
        angles = ", ".join(repr(float(a)) for a in self.angles.value)
        return f"Receptors({self.types!r}, [{angles}] * u.deg)"

    def __eq__(self, other):
        if not isinstance(other, Receptors):
            return NotImplemented
        return self.types == other.types and bool(np.all(self.angles == other.angles))

    def __hash__(self):
        return hash((self.types, tuple(self.angles.value)))

    def angle(self, receptor):
        """The angle of one receptor.

        Parameters
        ----------
        receptor : str
            One of `types` (any case).

        Returns
        -------
        `~astropy.coordinates.Angle`

        Raises
        ------
        ValueError
            If the feed has no such receptor.

        Examples
        --------
        >>> import astropy.units as u
        >>> from astropy_feedrot.antennas.receptors import Receptors
        >>> Receptors("YX", [0, 90] * u.deg).angle("x")
        <Angle 90. deg>
        """
        letter = str(receptor).strip().upper()
        if letter not in self.types:
            raise ValueError(f"this feed has receptors {tuple(self.types)}, not {receptor!r}")
        return self.angles[self.types.index(letter)]

    @property
    def sky_angles(self):
        """The angles :math:`\\alpha` with which the receptors turn on the sky.

        Those of the file for linear receptors; for circular ones the first
        receptor's angle for both (module docstring: CASA's rule).

        Returns
        -------
        `~astropy.coordinates.Angle`
            One per receptor, in the order of `types`.

        Examples
        --------
        >>> import astropy.units as u
        >>> from astropy_feedrot.antennas.receptors import Receptors
        >>> Receptors("RL", [20, 110] * u.deg).sky_angles
        <Angle [20., 20.] deg>
        >>> Receptors("XY", [-10, 80] * u.deg).sky_angles
        <Angle [-10.,  80.] deg>
        """
        if self.basis == "circular":
            return Angle(np.full(len(self.types), self.angles[0].to_value(u.deg)), u.deg)
        return self.angles

    @property
    def unusual_offset(self):
        """The angle (deg) of the second circular receptor from the first, if unusual.

        Returns
        -------
        float or None
            The offset in (-180, 180] deg when a circular feed gives its two
            receptors angles that differ by other than `CIRCULAR_OFFSETS`
            (whose second angle is then ignored: `sky_angles`); else None.

        Examples
        --------
        >>> import astropy.units as u
        >>> from astropy_feedrot.antennas.receptors import Receptors
        >>> Receptors("RL", [0, 90] * u.deg).unusual_offset is None
        True
        >>> Receptors("RL", [20, 50] * u.deg).unusual_offset
        30.0
        """
        if self.basis != "circular" or len(self.types) < 2:
            return None
        offset = float((self.angles[1] - self.angles[0]).to_value(u.deg)) % 360.0
        # Within 1e-3 deg: files store the angles in single precision (radians too).
        if np.min(np.abs(offset - np.array(CIRCULAR_OFFSETS + (360.0,)))) < 1e-3:
            return None
        return offset - 360.0 if offset > 180.0 else offset

    def position_angles(self, feed_rotation):
        """The position angles :math:`\\theta = \\Phi + \\alpha` of the receptors on the sky.

        :math:`\\alpha` are the `sky_angles`: for circular receptors the
        first receptor's angle for both.

        Parameters
        ----------
        feed_rotation : `~astropy.units.Quantity` or `~astropy.coordinates.Angle`
            The feed rotation :math:`\\Phi` of the antenna, any shape.

        Returns
        -------
        `~astropy.coordinates.Angle`
            Shape ``feed_rotation.shape + (len(types),)``, in the order of
            `types`, in degrees (not wrapped).

        Raises
        ------
        TypeError, astropy.units.UnitsError
            If ``feed_rotation`` is not an angle Quantity.

        Examples
        --------
        >>> import astropy.units as u
        >>> from astropy_feedrot.antennas.receptors import Receptors
        >>> Receptors("RL").position_angles([10, 20] * u.deg)  # doctest: +FLOAT_CMP
        <Angle [[10., 10.],
                [20., 20.]] deg>
        """
        if not isinstance(feed_rotation, u.Quantity):
            raise TypeError(f"feed_rotation must be an angle Quantity, got "
                            f"{type(feed_rotation).__name__}")
        if feed_rotation.unit.physical_type != "angle":
            raise u.UnitsError(f"feed_rotation must be an angle, got {feed_rotation.unit}")
        phi = feed_rotation.to_value(u.deg)
        return Angle(np.asarray(phi)[..., np.newaxis] + self.sky_angles.value, u.deg)

    def jones(self, feed_rotation):
        """The rows with which the receptors answer to the field on the sky.

        Parameters
        ----------
        feed_rotation : `~astropy.units.Quantity` or `~astropy.coordinates.Angle`
            The feed rotation :math:`\\Phi` of the antenna, any shape.

        Returns
        -------
        `~numpy.ndarray`
            Complex, shape ``feed_rotation.shape + (len(types), 2)``: row
            ``k`` gives the voltage of receptor ``k`` for unit fields toward
            north and toward east (module docstring).

        Raises
        ------
        TypeError, astropy.units.UnitsError
            If ``feed_rotation`` is not an angle Quantity.

        Examples
        --------
        A linear feed turned by 90 deg: X answers to the east field, Y to
        minus the north one:

        >>> import numpy as np
        >>> import astropy.units as u
        >>> from astropy_feedrot.antennas.receptors import Receptors
        >>> np.round(Receptors("XY").jones(90 * u.deg).real, 12) + 0.0
        array([[ 0.,  1.],
               [-1.,  0.]])
        """
        theta = self.position_angles(feed_rotation).to_value(u.rad)
        out = np.empty(theta.shape + (2,), dtype=complex)
        for k, letter in enumerate(self.types):
            t = theta[..., k]
            if letter in "XY":
                out[..., k, 0], out[..., k, 1] = np.cos(t), np.sin(t)
            else:
                hand = 1 if letter == "R" else -1
                phase = np.exp(-1j * hand * t) / np.sqrt(2)
                out[..., k, 0], out[..., k, 1] = phase, 1j * hand * phase
        return out
