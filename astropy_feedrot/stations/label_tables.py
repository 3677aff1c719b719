# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The mount labels of other software: the tables, their sources, and the normal
form under which a label is looked up.

`astropy_feedrot.stations.labels` reads and writes labels with these tables; each
convention of `SOFTWARE` is a tuple of ``(label, kind)`` pairs in `TABLES`,
and each kind of mount and focus is built by `MAKERS` (or has no model, for
the reason in `NO_MODEL`).

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

from ..antennas.focus import BeamWaveguideFocus, NasmythFocus
from ..antennas.mounts import AltAzMount, EquatorialMount, FixedAxisMount, StationaryMount, XYMount

__all__ = ["SOFTWARE", "TABLES", "KNOWN_LABELS", "LOOKUP", "MAKERS", "DESCRIPTIONS", "NO_MODEL",
           "NOTES", "OLD_ERAS", "VEX_NASMYTH", "RICHMOND_AXIS", "check_software", "label_key",
           "one_scalar"]

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
RICHMOND_AXIS = (
    np.cos(_RICH_ELEVATION) * np.sin(_RICH_AZIMUTH),
    np.cos(_RICH_ELEVATION) * np.cos(_RICH_AZIMUTH),
    np.sin(_RICH_ELEVATION),
)

# What each kind of label builds.
MAKERS = {
    "alt-az": lambda: (AltAzMount(), None),
    "equatorial": lambda: (EquatorialMount(), None),
    "xy-north": lambda: (XYMount("north"), None),
    "xy-east": lambda: (XYMount("east"), None),
    "richmond": lambda: (FixedAxisMount(RICHMOND_AXIS, frame="enu"), None),
    "nasmyth-right": lambda: (AltAzMount(), NasmythFocus("right")),
    "nasmyth-left": lambda: (AltAzMount(), NasmythFocus("left")),
    "bwg-right": lambda: (AltAzMount(), BeamWaveguideFocus("right")),
    "bwg-left": lambda: (AltAzMount(), BeamWaveguideFocus("left")),
    "stationary": lambda: (StationaryMount(), None),
}

DESCRIPTIONS = {
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
NO_MODEL = {
    "orbiting": _ORBITING,
    "phased": _PHASED,
    "other": _OTHER,
    "casacore-9": _CASACORE_9,
    "casacore-old-7": _CASACORE_OLD_7,
    "casacore-bizarre": _CASACORE_BIZARRE,
}

# Each convention: (label, kind) in order; the first label of a kind is the
# one written by label_from_mount.
TABLES = {
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
    {software: tuple(label for label, _ in table) for software, table in TABLES.items()}
)

#: VEX 2 ``nasmyth`` values and the focus each one gives an az:el antenna.
VEX_NASMYTH = {"none": None, "right": "right", "left": "left"}

# Notes added when a convention cannot write a kind.
NOTES = {
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


def one_scalar(label):
    """Unwrap a numpy scalar or 0-d array into a Python one; refuse arrays of labels.

    Parameters
    ----------
    label : object
        A label as read from a table.

    Returns
    -------
    object
        A Python int, float, str or bytes (anything else unchanged).

    Raises
    ------
    TypeError
        For an array with axes.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.stations.label_tables import one_scalar
    >>> one_scalar(np.int32(4)), one_scalar(np.array("ALT-AZ"))
    (4, 'ALT-AZ')
    """
    if isinstance(label, np.ndarray):
        if label.ndim:
            raise TypeError(f"give one label at a time, got an array of shape {label.shape}")
        return label.item()
    if isinstance(label, np.generic):
        return label.item()
    return label


def _code(label):
    """An integer MNTSTA code from an int, a whole float or a numeric string."""
    label = one_scalar(label)
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
    label = one_scalar(label)
    if isinstance(label, bytes):
        return label.decode("ascii", "replace")
    if not isinstance(label, str):
        raise TypeError(f"a mount label is a string, got {type(label).__name__}")
    return label


def label_key(software, label):
    """The normalized form of ``label`` under which ``software``'s table is searched.

    Parameters
    ----------
    software : str
        One of `SOFTWARE` (already checked, `check_software`).
    label : int, str or bytes
        The label.

    Returns
    -------
    int or str
        The ``MNTSTA`` code as an int for the ``fits-idi:*`` conventions; the
        VEX ``axis_type`` without blanks in lower case; other strings
        stripped, in upper case.

    Raises
    ------
    TypeError, ValueError
        For a label of the wrong kind (a code that is not a whole number).

    Examples
    --------
    >>> from astropy_feedrot.stations.label_tables import label_key
    >>> label_key("fits-idi:difx", "4"), label_key("casacore", " alt-az ")
    (4, 'ALT-AZ')
    >>> label_key("vex", "AZ : EL")
    'az:el'

    """
    if software.startswith("fits-idi:"):
        return _code(label)
    text = _text(label)
    if software == "vex":
        return "".join(text.split()).lower()
    return text.strip().upper()


LOOKUP = {
    software: {label_key(software, label): (label, kind) for label, kind in table}
    for software, table in TABLES.items()
}


def check_software(software):
    """The name of `SOFTWARE` that ``software`` stands for.

    Parameters
    ----------
    software : str
        A convention, in any case.

    Returns
    -------
    str

    Raises
    ------
    TypeError, ValueError
        For anything else; a bare ``'fits-idi'`` is told which conventions
        to choose from.

    Examples
    --------
    >>> from astropy_feedrot.stations.label_tables import check_software
    >>> check_software(" CASACORE ")
    'casacore'
    """
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


#: Older eras of a convention, not named in hints about other conventions.
OLD_ERAS = ("fits-idi:casacore<3.7", "fits-idi:casacore<3.2")
