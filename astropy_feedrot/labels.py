# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Mount labels of other software, to and from this package's mounts and foci.

Visibility files, correlator inputs and station catalogues name an antenna's
mount and focus with labels of their own: an integer ``MNTSTA`` code in the
antenna table of FITS-IDI and UVFITS files, a ``MOUNT`` string in a
Measurement Set, a DiFX mount name, a VEX ``axis_type``, a pyuvdata
``mount_type``, a geodetic station-catalogue code. `mount_from_label` turns
such a label into a ``(mount, focus)`` pair for `~astropy_feedrot.Antenna`;
`label_from_mount` writes one back, and refuses what a convention cannot
express. The ``MNTSTA`` codes 6 and 7 mean different things to casacore,
DiFX and pyuvdata, so a code is always read with the software that wrote it.

Sources
-------
Each table was checked against the code of the software itself (read, not
copied):

``fits-idi:casacore``
    casacore/casacore (commit ef9a25f): ``msfits/MSFits/FitsIDItoMS.cc``
    (FITS-IDI ``MNTSTA`` 0-7 to ``MOUNT``), ``msfits/MSFits/MSFitsInput.cc``
    and ``msfits/MSFits/MSFitsOutput.cc`` (UVFITS: also 8 = ``BIZARRE``,
    9 = ``SPACE-HALCA`` or unrecognised).
``casacore``
    casacore/casacore: ``ms/MSOper/MSDerivedValues.cc``
    (``setAntennaMount``: the strings it accepts, each in upper or lower case,
    ``""`` and ``ALT-AZ+ROTATOR`` as alt-az; ``parAngle``: the sign of each
    term), the ``MOUNT`` strings written by the FITS readers above.
``fits-idi:casacore<3.7``, ``fits-idi:casacore<3.2``
    The same files at the commits that changed the codes: ``21dd9c182``
    (2019, first in casacore 3.2.0: Nasmyth written as 4 and 5, ``BIZARRE``
    moved from 4 to 6) and ``d08694031`` / ``66d4316b9`` (2025, first in
    3.7.0: beam waveguides 6 and 7, ``BIZARRE`` 8, ``SPACE-HALCA`` and
    unrecognised mounts 9). Before 3.7 casacore wrote 7 for an orbiting or
    unrecognised mount; before 3.2 it wrote Nasmyth mounts as 0 and
    ``BIZARRE`` as 4. Such codes have no model here: a 6 or 7 of an old
    casacore is never read as a beam waveguide.
``fits-idi:difx``, ``difx``
    difx/difx (commit 9027301): ``libraries/difxio/difxio/difx_input.h``
    (``enum AntennaMountType``), ``libraries/difxio/difxio/difx_antenna.c``
    (``antennaMountTypeNames``, ``stringToMountType`` and its synonyms),
    ``applications/difx2fits/src/fitsAG.c`` (``MNTSTA`` is that enum).
``vex``
    difx/difx: ``applications/vex2difx/vexdatamodel/vexload.cpp``,
    ``applications/vex2difx/vexdatamodel/vex_antenna.cpp`` (VEX 2 ``nasmyth``
    per band: ``none``, ``right``, ``left``), ``applications/vex2difx/src/vex2difx.cpp``
    (a Nasmyth platform turns the mount into NASR/NASL) and the HOPS VEX
    parser ``applications/hops/sub/vex/do_antenna.c`` (the four axis types).
``pyuvdata``, ``fits-idi:pyuvdata``
    RadioAstronomySoftwareGroup/pyuvdata (commit a5f2aac):
    ``src/pyuvdata/telescopes.py`` (accepted ``mount_type`` values),
    ``src/pyuvdata/utils/antenna.py`` (``MOUNT_STR2NUM_DICT``, the codes it
    writes to UVFITS, calfits and Miriad), ``src/pyuvdata/uvdata/uvfits.py``,
    ``docs/conventions.rst``. pyuvdata has no FITS-IDI reader; its codes are
    those of its UVFITS files.
``geodetic``
    nasa/sgdass (commit 3e3cad5), Petrov's VTD library:
    ``vtd/src/vtd_load_stadesc.f`` (the accepted codes),
    ``vtd/src/vtd_axof.f`` (the fixed axis of each code, including ``RICH``),
    ``vtd/src/vtd_delay.f`` (its feed angles), ``pima/Changelog.txt`` (``BWG``
    introduced for WARK30M).

Beyond the common table
-----------------------
The eight rows of the usual table (codes 0-7) agree with the sources. The
sources add:

* casacore also writes and reads ``BIZARRE`` (8), ``SPACE_HALCA`` /
  ``SPACE-HALCA`` (9) and ``UNKNOWN``; pyuvdata also has ``other`` and
  ``bizarre`` (8); DiFX reads the synonyms ``ALTAZ``, ``EQUATORIAL``,
  ``NASMYTH-R`` and so on; VTD also knows ``RICH``, the Richmond antenna whose
  fixed axis points 39.06 deg above the northern horizon (a
  `~astropy_feedrot.FixedAxisMount`). All are accepted.
* X-Y without a direction (casacore ``X-Y``, pyuvdata ``x-y``, ``MNTSTA`` 3)
  is the X-Y mount with an **east-west** fixed axis: casacore's ``parAngle``
  computes ``atan2(-cos h, -sin h sin dec)`` for it and pyuvdata's
  conventions give ``arctan(cos h / (sin h sin dec))``, both the
  `~astropy_feedrot.XYMount` ``'east'`` form (the first up to 180 deg), and
  DiFX numbers XYEW 3. (pyuvdata's prose describes a north-south axis; its
  formula is followed.) So an X-Y mount with a north-south axis cannot be
  written in those conventions.
* difx2fits prints that XYNS "is being set to XYEW" but writes its enum
  value 6; ``fits-idi:difx`` code 6 is read as XYNS, as written.
* pyuvdata reads codes 7 and 8 of a UVFITS file it did not write as
  ``other``; ``fits-idi:pyuvdata`` follows the codes pyuvdata writes
  (7 = ``fixed``).
* casacore's FITS-IDI reader swapped codes 2 and 3 (read 2 as ``X-Y`` and 3
  as ``ORBITING``) before 3.5.0 (fixed in ``0fddd85cb``, 2021). That changes
  the ``MOUNT`` of a Measurement Set made from FITS-IDI by an older casacore,
  not the meaning of the codes in a FITS-IDI file, which DiFX writes as
  ``fits-idi:difx`` (2 orbiting, 3 X-Y east-west).
* The geodetic ``BWG`` code has no handedness, and VTD's feed angle for it is
  ``Psi - A``, without the elevation term of Eq 39 (and VTD's ``X-YE`` and
  ``X-YN`` feed angles are not the X-Y forms either). The codes are read as
  geometry (the fixed axes of ``vtd_axof.f``) and ``BWG`` as the paper's
  WARK30M, for which PIMA introduced it: a right-handed beam waveguide,
  ``Psi + E - A`` (Eq 39, Appendix C.2), as casacore's ``ALT-AZ+BWG-R``.

Traps
-----
The same label can give different feed rotations in different programs:

* Case and blanks. This package matches mount strings case-insensitively
  and strips blanks. casacore's ``MSDerivedValues::setAntennaMount``
  (``ms/MSOper/MSDerivedValues.cc``, used by CASA for its parallactic
  angles) compares exactly, with one upper- and one lower-case spelling
  each: ``"Alt-Az"`` or ``"ALT-AZ "`` (a trailing blank) is an unhandled
  mount there, whose parallactic angle is 0 with a warning.
* TaQL ``mscal.pa1()``/``pa2()`` (``derivedmscal/DerivedMC/MSCalEngine.cc``)
  lower-cases ``MOUNT`` and tests only the prefix ``alt-az``: it accepts
  ``"Alt-Az"``, but gives every ``ALT-AZ+NASMYTH-*`` and ``ALT-AZ+BWG-*``
  antenna the plain parallactic angle, without the Nasmyth or beam-waveguide
  terms, and gives 0 for every other mount.
* pyuvdata reads ``MNTSTA`` 6 of a UVFITS file it did not write as
  ``phased`` (``src/pyuvdata/uvdata/uvfits.py``), DiFX writes 6 for XYNS and
  7 for any other mount (``fitsAG.c``), and casacore 3.7 and later read 6 and
  7 as ``ALT-AZ+BWG-R`` and ``ALT-AZ+BWG-L`` (``FitsIDItoMS.cc``,
  ``MSFitsInput.cc``): a DiFX file imported by a recent casacore turns its
  X-Y north-south and "other" antennas into beam waveguides.
* casacore's UVFITS reader (``MSFitsInput::fillAntennaTable``) makes every
  antenna of a file whose ``TELESCOP`` is ``'SMA'`` alt-az, whatever its
  ``MNTSTA``, while pyuvdata describes the SMA antennas as left-handed
  Nasmyth (``alt-az+nasmyth-l``).
"""

import numbers
from types import MappingProxyType

import numpy as np

from .focus import (
    BeamWaveguideFocus,
    CassegrainFocus,
    GregorianFocus,
    MirrorTrain,
    NasmythFocus,
    PrimeFocus,
    as_focus,
)
from .mounts import (
    AltAzMount,
    EquatorialMount,
    FixedAxisMount,
    StationaryMount,
    XYMount,
    as_mount,
)

__all__ = ["SOFTWARE", "KNOWN_LABELS", "known_labels", "mount_from_label", "label_from_mount"]

#: The label conventions understood: ``MNTSTA`` codes as casacore, DiFX and
#: pyuvdata write and read them, and the mount strings of each program.
SOFTWARE = (
    "fits-idi:casacore",
    "fits-idi:difx",
    "fits-idi:pyuvdata",
    "fits-idi:casacore<3.7",
    "fits-idi:casacore<3.2",
    "casacore",
    "difx",
    "vex",
    "pyuvdata",
    "geodetic",
)

# Fixed axis of VTD's 'RICH' code (vtd_axof.f): 39d03m36s above the horizon,
# 0d07m12s west of north, as east-north-up components.
_RICH_ELEVATION = np.radians(39 + 3 / 60 + 36 / 3600)
_RICH_AZIMUTH = -np.radians(7 / 60 + 12 / 3600)
_RICHMOND_AXIS = (
    np.cos(_RICH_ELEVATION) * np.sin(_RICH_AZIMUTH),
    np.cos(_RICH_ELEVATION) * np.cos(_RICH_AZIMUTH),
    np.sin(_RICH_ELEVATION),
)

# What each kind of label builds.
_MAKERS = {
    "alt-az": lambda: (AltAzMount(), None),
    "equatorial": lambda: (EquatorialMount(), None),
    "xy-north": lambda: (XYMount("north"), None),
    "xy-east": lambda: (XYMount("east"), None),
    "richmond": lambda: (FixedAxisMount(_RICHMOND_AXIS, frame="enu"), None),
    "nasmyth-right": lambda: (AltAzMount(), NasmythFocus("right")),
    "nasmyth-left": lambda: (AltAzMount(), NasmythFocus("left")),
    "bwg-right": lambda: (AltAzMount(), BeamWaveguideFocus("right")),
    "bwg-left": lambda: (AltAzMount(), BeamWaveguideFocus("left")),
    "stationary": lambda: (StationaryMount(), None),
}

_DESCRIPTIONS = {
    "alt-az": "an alt-az mount (AltAzMount())",
    "equatorial": "an equatorial mount (EquatorialMount())",
    "xy-north": "an X-Y mount with a north-south fixed axis (XYMount('north'))",
    "xy-east": "an X-Y mount with an east-west fixed axis (XYMount('east'))",
    "richmond": "the fixed axis of the Richmond antenna (geodetic 'RICH')",
    "nasmyth-right": "an alt-az mount with a right-handed Nasmyth focus (NasmythFocus('right'))",
    "nasmyth-left": "an alt-az mount with a left-handed Nasmyth focus (NasmythFocus('left'))",
    "bwg-right": ("an alt-az mount with a right-handed beam-waveguide focus "
                  "(BeamWaveguideFocus('right'))"),
    "bwg-left": ("an alt-az mount with a left-handed beam-waveguide focus "
                 "(BeamWaveguideFocus('left'))"),
    "stationary": "a stationary antenna (StationaryMount())",
}

# Labels with no feed-rotation model here, and why.
_ORBITING = (
    "an orbiting antenna (space VLBI) turns with its spacecraft, so its feed rotation "
    "needs an attitude model that a mount label does not carry; this package models "
    "orbiting transmitters (Satellite), not orbiting receivers"
)
_PHASED = (
    "the feed rotation of a phased array (an electronically steered beam) is that of its "
    "elements, which the label does not describe; for elements fixed to the ground use "
    "StationaryMount()"
)
_OTHER = (
    "the label says the mount is unknown or unusual; give the mount and focus "
    "explicitly (e.g. AltAzMount(), FixedAxisMount(...), MirrorTrain(...))"
)
_CASACORE_9 = (
    "casacore writes MNTSTA 9 for an orbiting antenna (SPACE-HALCA) and for any mount it "
    "does not recognise; give the mount and focus explicitly"
)
_CASACORE_OLD_7 = (
    "casacore before 3.7 writes MNTSTA 7 for an orbiting antenna (SPACE-HALCA) and for any "
    "mount it does not recognise, beam waveguides included (BWG codes 6 and 7 arrived in "
    "casacore 3.7); give the mount and focus explicitly"
)
_CASACORE_BIZARRE = (
    "casacore before 3.7 writes this code for a 'BIZARRE' mount, not for a beam waveguide "
    "(BWG codes 6 and 7 arrived in casacore 3.7); give the mount and focus explicitly"
)
_NO_MODEL = {
    "orbiting": _ORBITING,
    "phased": _PHASED,
    "other": _OTHER,
    "casacore-9": _CASACORE_9,
    "casacore-old-7": _CASACORE_OLD_7,
    "casacore-bizarre": _CASACORE_BIZARRE,
}

# Each convention: (label, kind) in order; the first label of a kind is the
# one written by label_from_mount.
_TABLES = {
    "fits-idi:casacore": (
        (0, "alt-az"), (1, "equatorial"), (2, "orbiting"), (3, "xy-east"),
        (4, "nasmyth-right"), (5, "nasmyth-left"), (6, "bwg-right"), (7, "bwg-left"),
        (8, "other"), (9, "casacore-9"),
    ),
    # casacore 3.2-3.6: MSFitsOutput writes BIZARRE as 6 and everything it does
    # not recognise (SPACE-HALCA, BWG) as 7.
    "fits-idi:casacore<3.7": (
        (0, "alt-az"), (1, "equatorial"), (2, "orbiting"), (3, "xy-east"),
        (4, "nasmyth-right"), (5, "nasmyth-left"), (6, "casacore-bizarre"),
        (7, "casacore-old-7"),
    ),
    # casacore 2.0-3.1: no Nasmyth codes (written as 0); BIZARRE is 4 (read
    # back from 4, 5 or 6), everything else 7.
    "fits-idi:casacore<3.2": (
        (0, "alt-az"), (1, "equatorial"), (2, "orbiting"), (3, "xy-east"),
        (4, "casacore-bizarre"), (5, "casacore-bizarre"), (6, "casacore-bizarre"),
        (7, "casacore-old-7"),
    ),
    "fits-idi:difx": (
        (0, "alt-az"), (1, "equatorial"), (2, "orbiting"), (3, "xy-east"),
        (4, "nasmyth-right"), (5, "nasmyth-left"), (6, "xy-north"), (7, "other"),
    ),
    "fits-idi:pyuvdata": (
        (0, "alt-az"), (1, "equatorial"), (2, "orbiting"), (3, "xy-east"),
        (4, "nasmyth-right"), (5, "nasmyth-left"), (6, "phased"), (7, "stationary"),
        (8, "other"),
    ),
    "casacore": (
        ("ALT-AZ", "alt-az"), ("", "alt-az"), ("ALT-AZ+ROTATOR", "alt-az"),
        ("EQUATORIAL", "equatorial"),
        ("ORBITING", "orbiting"), ("SPACE-HALCA", "orbiting"), ("SPACE_HALCA", "orbiting"),
        ("X-Y", "xy-east"),
        ("ALT-AZ+NASMYTH-R", "nasmyth-right"), ("ALT-AZ+NASMYTH-L", "nasmyth-left"),
        ("ALT-AZ+BWG-R", "bwg-right"), ("ALT-AZ+BWG-L", "bwg-left"),
        ("BIZARRE", "other"), ("UNKNOWN", "other"),
    ),
    "difx": (
        ("AZEL", "alt-az"), ("ALTAZ", "alt-az"), ("ALTZ", "alt-az"),
        ("EQUA", "equatorial"), ("EQUAT", "equatorial"), ("EQUATORIAL", "equatorial"),
        ("HADEC", "equatorial"),
        ("SPACE", "orbiting"), ("SPAC", "orbiting"), ("ORBIT", "orbiting"),
        ("ORBI", "orbiting"), ("ORBITING", "orbiting"),
        ("XYEW", "xy-east"),
        ("NASR", "nasmyth-right"), ("NASMYTH-R", "nasmyth-right"),
        ("NASMYTHR", "nasmyth-right"),
        ("NASL", "nasmyth-left"), ("NASMYTH-L", "nasmyth-left"), ("NASMYTHL", "nasmyth-left"),
        ("XYNS", "xy-north"),
        ("OTHER", "other"),
    ),
    "vex": (
        ("az:el", "alt-az"), ("ha:dec", "equatorial"), ("x:yew", "xy-east"),
        ("x:yns", "xy-north"),
    ),
    "pyuvdata": (
        ("alt-az", "alt-az"), ("equatorial", "equatorial"), ("orbiting", "orbiting"),
        ("x-y", "xy-east"), ("alt-az+nasmyth-r", "nasmyth-right"),
        ("alt-az+nasmyth-l", "nasmyth-left"), ("phased", "phased"), ("fixed", "stationary"),
        ("other", "other"), ("bizarre", "other"),
    ),
    "geodetic": (
        ("AZEL", "alt-az"), ("EQUA", "equatorial"), ("X-YN", "xy-north"),
        ("X-YE", "xy-east"), ("RICH", "richmond"),
        ("NASR", "nasmyth-right"), ("NASP", "nasmyth-right"),
        ("NASL", "nasmyth-left"), ("NASM", "nasmyth-left"),
        ("BWG", "bwg-right"), ("GNSS", "stationary"),
    ),
}

#: For each name of `SOFTWARE`, the tuple of labels `mount_from_label`
#: accepts (strings are matched case-insensitively).
KNOWN_LABELS = MappingProxyType(
    {software: tuple(label for label, _ in table) for software, table in _TABLES.items()}
)

#: VEX 2 ``nasmyth`` values and the focus each one gives an az:el antenna.
_VEX_NASMYTH = {"none": None, "right": "right", "left": "left"}

# Notes added when a convention cannot write a kind.
_NOTES = {
    ("fits-idi:casacore", "xy-north"): "its code 3 (X-Y) is the east-west form",
    ("fits-idi:pyuvdata", "xy-north"): "its code 3 (x-y) is the east-west form",
    ("fits-idi:casacore<3.7", "xy-north"): "its code 3 (X-Y) is the east-west form",
    ("fits-idi:casacore<3.2", "xy-north"): "its code 3 (X-Y) is the east-west form",
    ("fits-idi:casacore<3.7", "bwg-right"): "casacore before 3.7 wrote it as 0 (ALT-AZ)",
    ("fits-idi:casacore<3.7", "bwg-left"): "casacore before 3.7 wrote it as 0 (ALT-AZ)",
    ("fits-idi:casacore<3.2", "bwg-right"): "casacore before 3.7 wrote it as 0 (ALT-AZ)",
    ("fits-idi:casacore<3.2", "bwg-left"): "casacore before 3.7 wrote it as 0 (ALT-AZ)",
    ("fits-idi:casacore<3.2", "nasmyth-right"): "casacore before 3.2 wrote it as 0 (ALT-AZ)",
    ("fits-idi:casacore<3.2", "nasmyth-left"): "casacore before 3.2 wrote it as 0 (ALT-AZ)",
    ("casacore", "xy-north"): "its 'X-Y' is the east-west form",
    ("pyuvdata", "xy-north"): "its 'x-y' is the east-west form",
    ("geodetic", "bwg-left"): "its one code 'BWG' is the right-handed form of WARK30M",
}


def _one_scalar(label):
    """Unwrap a numpy scalar or 0-d array into a Python one; refuse arrays of labels."""
    if isinstance(label, np.ndarray):
        if label.ndim:
            raise TypeError(f"give one label at a time, got an array of shape {label.shape}")
        return label.item()
    if isinstance(label, np.generic):
        return label.item()
    return label


def _code(label):
    """An integer MNTSTA code from an int, a whole float or a numeric string."""
    label = _one_scalar(label)
    if isinstance(label, (bool, np.bool_)):
        raise TypeError(f"a MNTSTA code is an integer, got the bool {label!r}")
    if isinstance(label, numbers.Integral):
        return int(label)
    if isinstance(label, bytes):
        label = label.decode("ascii", "replace")
    if isinstance(label, str):
        text = label.strip()
        try:
            return int(text)
        except ValueError:
            pass
        try:
            value = float(text)
        except ValueError:
            raise ValueError(f"a MNTSTA code is an integer, got {label!r}") from None
    elif isinstance(label, numbers.Real):
        value = float(label)
    else:
        raise TypeError(f"a MNTSTA code is an integer, got {type(label).__name__}")
    if not (np.isfinite(value) and value.is_integer()):
        raise ValueError(f"a MNTSTA code is a whole number, got {label!r}")
    return int(value)


def _text(label):
    """A mount string from a str or bytes."""
    label = _one_scalar(label)
    if isinstance(label, bytes):
        return label.decode("ascii", "replace")
    if not isinstance(label, str):
        raise TypeError(f"a mount label is a string, got {type(label).__name__}")
    return label


def _key(software, label):
    """The normalized form of ``label`` under which ``software``'s table is searched."""
    if software.startswith("fits-idi:"):
        return _code(label)
    text = _text(label)
    if software == "vex":
        return "".join(text.split()).lower()
    return text.strip().upper()


_LOOKUP = {
    software: {_key(software, label): (label, kind) for label, kind in table}
    for software, table in _TABLES.items()
}


def _check_software(software):
    """The name of SOFTWARE that ``software`` stands for."""
    if software is None:
        raise ValueError(f"software is required: one of {SOFTWARE}")
    if not isinstance(software, str):
        raise TypeError(f"software must be a string, one of {SOFTWARE}; got "
                        f"{type(software).__name__}")
    name = software.strip().lower()
    if name in SOFTWARE:
        return name
    hint = ""
    if name in ("fits-idi", "fitsidi", "fits", "uvfits", "idi", "mntsta"):
        hint = (" MNTSTA codes 6 and 7 mean different mounts to casacore (beam waveguide), "
                "DiFX (XYNS, other) and pyuvdata (phased, fixed): say whose convention, "
                "e.g. 'fits-idi:casacore', 'fits-idi:difx' or 'fits-idi:pyuvdata'.")
    raise ValueError(f"unknown software {software!r}; expected one of {SOFTWARE}.{hint}")


def known_labels(software):
    """The labels of a software's convention that `mount_from_label` accepts.

    Parameters
    ----------
    software : str
        One of `SOFTWARE`.

    Returns
    -------
    list
        Integers for the ``fits-idi:*`` conventions, strings otherwise (the
        VEX ones are ``axis_type`` values). Strings are matched
        case-insensitively, so each is listed once, in the case the software
        writes it. Labels with no feed-rotation model (orbiting, phased,
        other) are included: they are known, and rejected with a reason.

    Raises
    ------
    ValueError
        For an unknown ``software``.

    Examples
    --------
    >>> from astropy_feedrot.labels import known_labels
    >>> known_labels("geodetic")
    ['AZEL', 'EQUA', 'X-YN', 'X-YE', 'RICH', 'NASR', 'NASP', 'NASL', 'NASM', 'BWG', 'GNSS']
    """
    return list(KNOWN_LABELS[_check_software(software)])


def _join(words, conjunction="and"):
    words = list(words)
    if len(words) == 1:
        return words[0]
    return ", ".join(words[:-1]) + f" {conjunction} " + words[-1]


def _shown(software, label):
    """A label as the text of a message."""
    if software == "vex":
        axis_type, nasmyth = label
        return f"axis_type {axis_type!r}" + (f", nasmyth {nasmyth!r}" if nasmyth else "")
    return repr(label)


# Older eras of a convention, not named in hints about other conventions.
_OLD_ERAS = ("fits-idi:casacore<3.7", "fits-idi:casacore<3.2")


def _elsewhere(label, software):
    """A hint naming the other conventions that know ``label``, or ''."""
    others = []
    for other in SOFTWARE:
        if other == software or other in _OLD_ERAS:
            continue
        try:
            key = _key(other, label)
        except (TypeError, ValueError):
            continue
        if key in _LOOKUP[other]:
            others.append(other)
    if not others:
        return ""
    hint = (f"{label!r} is a {_join(others)} label; use "
            + " or ".join(f"software={other!r}" for other in others))
    codes = [other for other in others if other.startswith("fits-idi:")]
    if len(codes) > 1 and _key(codes[0], label) in (6, 7):
        hint += " (codes 6 and 7 mean different mounts to each)"
    return hint


def _listing(software):
    return ", ".join(repr(label) for label in KNOWN_LABELS[software])


def _lookup(software, label):
    """The kind of ``label`` in ``software``'s table; ValueError if unknown."""
    try:
        key = _key(software, label)
    except (TypeError, ValueError):
        hint = _elsewhere(label, software)
        if hint:
            raise ValueError(f"{label!r} is not a {software} mount label: {hint}") from None
        raise
    entry = _LOOKUP[software].get(key)
    if entry is None:
        hint = _elsewhere(label, software)
        hint = f"; {hint}" if hint else ""
        what = "axis_type" if software == "vex" else "mount label"
        raise ValueError(
            f"unknown {software} {what} {label!r}{hint}. The {software} labels are "
            f"{_listing(software)}"
        )
    return entry


def _vex_focus(nasmyth, axis_type, kind):
    """The focus of a VEX 2 per-band ``nasmyth`` value."""
    if nasmyth is None:
        return None
    if isinstance(nasmyth, bytes):
        nasmyth = nasmyth.decode("ascii", "replace")
    if not isinstance(nasmyth, str):
        raise TypeError(f"VEX nasmyth must be a string ('right', 'left' or 'none') or None, "
                        f"got {type(nasmyth).__name__}")
    value = nasmyth.strip().lower()
    if value not in _VEX_NASMYTH:
        raise ValueError(f"VEX nasmyth must be one of {tuple(_VEX_NASMYTH)} or None, got "
                         f"{nasmyth!r}")
    handedness = _VEX_NASMYTH[value]
    if handedness is None:
        return None
    if kind != "alt-az":
        raise ValueError(
            f"VEX nasmyth = {value} needs axis_type az:el (a Nasmyth focus is defined for an "
            f"alt-az mount), got {axis_type!r}; describe other optics with a MirrorTrain"
        )
    return NasmythFocus(handedness)


def mount_from_label(label, software, *, nasmyth=None):
    """The mount and focus named by another software's mount label.

    Parameters
    ----------
    label : int, str, or a 1-d sequence or array of them
        One label, or a column of labels (a list, tuple or 1-d numpy array
        of strings or integers, e.g. the ``MNTSTA`` column of an antenna
        table). For the ``fits-idi:*`` conventions, the ``MNTSTA`` code of the
        antenna table (an integer, a numpy integer or an integer-valued
        string such as ``"4"``). Otherwise the mount string, matched
        case-insensitively after stripping blanks: a Measurement Set
        ``MOUNT`` (``"casacore"``), a DiFX mount (``"difx"``), a VEX
        ``$ANTENNA`` ``axis_type`` such as ``"az:el"`` or ``"x:yns"``
        (``"vex"``; blanks anywhere are ignored), a pyuvdata ``mount_type``
        (``"pyuvdata"``) or a station-catalogue code (``"geodetic"``).
        `known_labels` lists them.
    software : str
        Whose convention: one of `SOFTWARE`.
    nasmyth : {'right', 'left', 'none'}, optional
        VEX 2 only: the ``nasmyth`` value of the band observed; ``'right'``
        or ``'left'`` turns ``az:el`` into a Nasmyth focus.

    Returns
    -------
    tuple or list of tuple
        For one label, the pair ``(mount, focus)`` below; for a column, a
        list with one such pair per label.
    mount : `~astropy_feedrot.mounts.Mount`
        `~astropy_feedrot.AltAzMount`, `~astropy_feedrot.EquatorialMount`,
        `~astropy_feedrot.XYMount`, `~astropy_feedrot.StationaryMount` (pyuvdata
        ``fixed``, geodetic ``GNSS``), or a `~astropy_feedrot.FixedAxisMount`
        (geodetic ``RICH``).
    focus : `~astropy_feedrot.focus.Focus` or None
        `~astropy_feedrot.NasmythFocus` or `~astropy_feedrot.BeamWaveguideFocus`
        when the label names one; None when it says nothing about the focus
        (`~astropy_feedrot.Antenna` then assumes a Cassegrain focus, and a
        prime or Gregorian focus gives the same feed rotation).

    Raises
    ------
    ValueError
        For an unknown ``software``; for a label the convention does not
        know (the message lists the ones it knows, and names the conventions
        that do know the label, if any); for a label with no feed-rotation
        model here (orbiting antennas, phased arrays, "other"); for a code
        that is not a whole number; for a bad ``nasmyth``, or one given for
        another axis type or another software.
    TypeError
        For a label of the wrong kind (a bool, a float for a mount string, a
        column of more than one dimension).

    The errors of a column name the row (``labels[3]: ...``).

    Notes
    -----
    The foci follow the signs of casacore, DiFX/HOPS, pyuvdata and VTD:
    Nasmyth right is :math:`\\Psi + E` and left :math:`\\Psi - E` (Eq 38),
    beam waveguide right :math:`\\Psi + E - A` and left :math:`\\Psi - E + A`
    (Eq 39). The module docstring gives the source file checked for each
    convention, and how X-Y without a direction (the east-west form) and the
    geodetic ``BWG`` (right-handed) are read.

    Examples
    --------
    >>> from astropy_feedrot.labels import mount_from_label
    >>> mount_from_label("ALT-AZ+BWG-R", "casacore")
    (AltAzMount(), BeamWaveguideFocus(handedness='right'))
    >>> mount_from_label("x:yns", "vex")
    (XYMount(axis='north'), None)
    >>> mount_from_label("az:el", "vex", nasmyth="right")
    (AltAzMount(), NasmythFocus(handedness='right'))

    ``MNTSTA`` 6 depends on who wrote the file:

    >>> mount_from_label(6, "fits-idi:casacore")
    (AltAzMount(), BeamWaveguideFocus(handedness='right'))
    >>> mount_from_label(6, "fits-idi:difx")
    (XYMount(axis='north'), None)

    and, for casacore, on its version (6 was ``BIZARRE`` before 3.7):

    >>> mount_from_label(6, "fits-idi:casacore<3.7")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: 6 (fits-idi:casacore<3.7) has no feed-rotation model here: ... 'BIZARRE' ...

    A column of labels gives a list of pairs:

    >>> import numpy as np
    >>> mount_from_label(np.array([0, 4]), "fits-idi:difx")
    [(AltAzMount(), None), (AltAzMount(), NasmythFocus(handedness='right'))]
    """
    software = _check_software(software)
    if nasmyth is not None and software != "vex":
        raise ValueError(f"nasmyth is the VEX 2 per-band value, for software='vex' only; "
                         f"the {software} label carries the focus itself")
    if _is_column(label):
        return _column(label, software, nasmyth)
    return _one(_one_scalar(label), software, nasmyth)


def _is_column(label):
    """Whether ``label`` is a column of labels (a list, tuple or array with axes)."""
    return isinstance(label, (list, tuple)) or (isinstance(label, np.ndarray) and label.ndim)


def _column(labels, software, nasmyth):
    """``[(mount, focus), ...]`` for a 1-d column of labels; errors name the row."""
    if isinstance(labels, np.ndarray) and labels.ndim != 1:
        raise TypeError(f"a column of labels is 1-d, got an array of shape {labels.shape}")
    pairs = []
    for row, label in enumerate(labels):
        if _is_column(label):
            raise TypeError(f"labels[{row}] is itself a sequence ({label!r}); give a flat "
                            "column of labels")
        try:
            pairs.append(_one(_one_scalar(label), software, nasmyth))
        except (TypeError, ValueError) as error:
            raise type(error)(f"labels[{row}]: {error}") from None
    return pairs


def _one(label, software, nasmyth):
    """The (mount, focus) of one scalar label."""
    _, kind = _lookup(software, label)
    if kind not in _MAKERS:
        raise ValueError(f"{label!r} ({software}) has no feed-rotation model here: "
                         f"{_NO_MODEL[kind]}")
    mount, focus = _MAKERS[kind]()
    if software == "vex":
        focus = _vex_focus(nasmyth, label, kind)
    return mount, focus


_AXES = {
    "alt-az": ("enu", (0.0, 0.0, 1.0)),
    "equatorial": ("itrs", (0.0, 0.0, 1.0)),
    "xy-north": ("enu", (0.0, 1.0, 0.0)),
    "xy-east": ("enu", (1.0, 0.0, 0.0)),
    "richmond": ("enu", _RICHMOND_AXIS),
}


def _axis_kind(mount):
    """The kind of a fixed-axis mount from its axis, or None for another axis."""
    for kind, (frame, axis) in _AXES.items():
        if mount.frame == frame and np.allclose(mount.axis, axis, rtol=0, atol=1e-12):
            return kind
    return None


def _kind(mount, focus):
    """The kind of label a mount and focus need; ValueError if no convention has one."""
    if isinstance(focus, MirrorTrain):
        raise ValueError(
            f"no software labels a MirrorTrain ({focus!r}): it is traced mirror by mirror. "
            "Label the closed form it reduces to instead: MirrorTrain.yebes40m() is "
            "NasmythFocus('right') and MirrorTrain.wark30m() BeamWaveguideFocus('right'), "
            "each up to a constant"
        )
    conventional = focus is None or isinstance(focus, (PrimeFocus, CassegrainFocus,
                                                       GregorianFocus))
    if isinstance(mount, StationaryMount):
        if not conventional:
            raise ValueError(f"a StationaryMount has no optics to add terms; {focus!r} "
                             "needs a steerable mount")
        return "stationary"
    if not isinstance(mount, FixedAxisMount):
        raise ValueError(f"no software labels the mount {mount!r}")
    kind = _axis_kind(mount)
    if kind is None:
        raise ValueError(
            f"no software labels the fixed axis of {mount!r}: the labels name the local "
            "vertical (alt-az), the celestial pole (equatorial), a horizontal north-south "
            "or east-west axis (X-Y) and the Richmond axis (geodetic 'RICH'); pass the "
            "FixedAxisMount to Antenna directly"
        )
    if conventional:
        return kind
    if not isinstance(focus, (NasmythFocus, BeamWaveguideFocus)):
        raise ValueError(f"no software labels the focus {focus!r}")
    if kind != "alt-az":
        raise ValueError(f"{type(focus).__name__} is defined for an AltAzMount, not for "
                         f"{mount!r}; no software labels that combination")
    prefix = "nasmyth" if isinstance(focus, NasmythFocus) else "bwg"
    return f"{prefix}-{focus.handedness}"


def _written(software, kind):
    """The label ``software`` writes for ``kind``, or None."""
    for label, known in _TABLES[software]:
        if known == kind:
            if software == "vex":
                return label, None
            return label
    if software == "vex" and kind.startswith("nasmyth-"):
        return "az:el", kind[len("nasmyth-"):]
    return None


def label_from_mount(mount, focus=None, software=None):
    """The label another software uses for a mount and focus.

    Parameters
    ----------
    mount : `~astropy_feedrot.mounts.Mount`
        `~astropy_feedrot.AltAzMount`, `~astropy_feedrot.EquatorialMount`,
        `~astropy_feedrot.XYMount`, `~astropy_feedrot.StationaryMount`, or a
        `~astropy_feedrot.FixedAxisMount` whose axis is one of those (or
        VTD's Richmond axis).
    focus : `~astropy_feedrot.focus.Focus`, optional
        None, `~astropy_feedrot.PrimeFocus`, `~astropy_feedrot.CassegrainFocus`
        or `~astropy_feedrot.GregorianFocus` (all give the plain label of the
        mount), or `~astropy_feedrot.NasmythFocus` /
        `~astropy_feedrot.BeamWaveguideFocus` on an alt-az mount.
    software : str
        Whose convention: one of `SOFTWARE` (required).

    Returns
    -------
    int, str or tuple
        The ``MNTSTA`` code (int) for the ``fits-idi:*`` conventions; for
        ``"vex"`` the tuple ``(axis_type, nasmyth)`` with ``nasmyth``
        ``'right'``, ``'left'`` or None (no ``nasmyth`` statement); the
        mount string otherwise, in the case the software writes it.

    Raises
    ------
    TypeError
        If ``mount`` or ``focus`` is not an instance of the package's classes.
    ValueError
        For an unknown or missing ``software``; if no convention labels the
        combination (a `~astropy_feedrot.MirrorTrain`, another fixed axis, a
        Nasmyth or beam-waveguide focus on another mount); if this
        ``software`` cannot express it (e.g. a beam waveguide in DiFX, VEX
        or pyuvdata, a north-south X-Y mount in casacore or pyuvdata, whose
        X-Y is the east-west one): the message names the conventions that
        can.

    Examples
    --------
    >>> from astropy_feedrot import AltAzMount, NasmythFocus, XYMount
    >>> from astropy_feedrot.labels import label_from_mount
    >>> label_from_mount(AltAzMount(), NasmythFocus("left"), software="casacore")
    'ALT-AZ+NASMYTH-L'
    >>> label_from_mount(AltAzMount(), NasmythFocus("left"), software="fits-idi:difx")
    5
    >>> label_from_mount(AltAzMount(), NasmythFocus("right"), software="vex")
    ('az:el', 'right')
    >>> label_from_mount(XYMount("north"), software="geodetic")
    'X-YN'
    """
    software = _check_software(software)
    mount = as_mount(mount)
    if focus is not None:
        focus = as_focus(focus)
    kind = _kind(mount, focus)
    label = _written(software, kind)
    if label is not None:
        return label
    note = _NOTES.get((software, kind))
    note = f"; {note}" if note else ""
    others = [(other, _written(other, kind)) for other in SOFTWARE
              if other != software and other not in _OLD_ERAS]
    others = [f"{other} ({_shown(other, label)})" for other, label in others
              if label is not None]
    raise ValueError(f"{software} has no mount label for {_DESCRIPTIONS[kind]}{note}. It can "
                     f"be labelled in {_join(others, 'or')}")
