# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""One correction, whatever the format: its options held once, its steps in one place.

A `Correction` checks its options when it is made (direction, frame,
convention or vertical and pole, receptors, mounts and catalogue,
ionosphere, redo) and takes the steps every format shares: the antennas
resolved (`~astropy_feedrot.visibilities.resolve.resolve_antennas`: aperture
arrays, the catalogue's mounts, the receptors given; then
`~astropy_feedrot.visibilities.unusable.usable_antennas`, which refuses with
every antenna's reason), the history checked and written
(`~astropy_feedrot.visibilities.history`), the pole of the parallactic
angle (`~astropy_feedrot.visibilities.poles`). Each format is an adapter
that reads its rows and writes its results, registered here by the kinds
of file it corrects (`register_adapter`), as astropy's I/O registry
registers readers: `Correction.correct` finds the adapter of a file by its
content (`~astropy_feedrot.visibilities.file_kind`).

The functions of the formats (`~astropy_feedrot.visibilities.correct_ms`,
`~astropy_feedrot.visibilities.correct_fitsidi`,
`~astropy_feedrot.visibilities.correct_uvdata`,
`~astropy_feedrot.visibilities.correct_processing_set`,
`~astropy_feedrot.visibilities.correct_file`) are short calls of one.
"""
from typing import Callable, NamedTuple

from ..earth.frames import VERTICALS
from .catalogue import check_mounts_option
from .faraday import check_ionosphere, ionosphere_text
from .history import check_direction, check_history, history_entry
from .kinds import check_output_format, check_output_path, existing_path, file_kind
from .poles import POLES, convention_options, pole_context
from .resolve import refuse_aperture_array, resolve_antennas
from .unusable import usable_antennas

__all__ = ["Correction", "Adapter", "register_adapter", "adapter_of", "OPTIONS",
           "refuse_column_options"]

#: The options a `Correction` holds, which every function of the formats takes.
OPTIONS = ("direction", "frame", "convention", "vertical", "pole", "feeds", "mounts",
           "catalogue", "ionosphere", "redo")

# kind of file -> its adapter (Adapter)
_ADAPTERS = {}


class Adapter(NamedTuple):
    """What a format registers: how to correct one of its files, and how to read the
    telescope names it gives (before anything else is read)."""

    correct: Callable
    telescopes: Callable


def register_adapter(kinds, correct, telescopes):
    """Register the functions that correct files of these kinds.

    Parameters
    ----------
    kinds : iterable of str
        Kinds of `~astropy_feedrot.visibilities.FILE_KINDS`.
    correct : callable
        ``correct(correction, path, output, **options)``: corrects the file
        at ``path`` into ``output`` (None: in place) as a `Correction`
        says; returns the path written.
    telescopes : callable
        ``telescopes(path)``: the telescope names the file gives, read
        without its data.

    Examples
    --------
    >>> from astropy_feedrot.visibilities.correction import adapter_of
    >>> adapter_of("fits-idi").correct.__name__
    'correct_fitsidi_file'
    """
    for kind in kinds:
        _ADAPTERS[kind] = Adapter(correct, telescopes)


def adapter_of(kind):
    """The `Adapter` registered for a kind of file (ValueError for none).

    Examples
    --------
    >>> from astropy_feedrot.visibilities.correction import adapter_of
    >>> adapter_of("vex")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: no adapter corrects files of kind 'vex'; the kinds corrected are ['fits-idi', ...
    """
    try:
        return _ADAPTERS[kind]
    except KeyError:
        raise ValueError(f"no adapter corrects files of kind {kind!r}; the kinds corrected "
                         f"are {sorted(_ADAPTERS)}") from None


def refuse_column_options(data_column=None, corrected_column="CORRECTED_DATA",
                          overwrite_column=False):
    """Refuse the column options of a Measurement Set where no Measurement Set is
    written.

    Examples
    --------
    >>> from astropy_feedrot.visibilities.correction import refuse_column_options
    >>> refuse_column_options()
    >>> refuse_column_options(data_column="MODEL_DATA")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: data_column, corrected_column and overwrite_column are for a Measurement ...
    """
    if data_column is not None or overwrite_column or corrected_column != "CORRECTED_DATA":
        raise ValueError("data_column, corrected_column and overwrite_column are for a "
                         "Measurement Set written as a Measurement Set (.ms)")


class Correction:
    """The feed rotation removed from (or applied to) visibilities: the options, once.

    Parameters
    ----------
    direction : {'remove', 'apply'}, optional
        ``'remove'`` (default): from the visibilities of the receptors as
        they turn, those of receptors fixed on the sky (R and L, or X north
        and Y east of ``frame``). ``'apply'``: the inverse, from a sky
        model to what the turning receptors see.
    frame : str, optional
        North of the sky-fixed receptors: ``'apparent'`` (default, the pole
        of date) or a celestial frame such as ``'icrs'``
        (`~astropy_feedrot.visibilities.frame_position_angle`).
    convention : {'rigorous', 'casa'}, optional
        The vertical and pole of `~astropy_feedrot.visibilities.poles.CONVENTIONS`:
        ``'rigorous'`` (default: geodetic, Earth-fixed pole) or ``'casa'``
        (CASA's applycal: geocentric, no polar motion); ``vertical`` and
        ``pole`` given explicitly replace its choices.
    vertical : {'geodetic', 'geocentric'}, optional
        The antennas' local vertical (default: the convention's;
        ``'geocentric'`` reproduces CASA).
    pole : {'itrs', 'casa'}, optional
        The pole of the parallactic angle (default: the convention's;
        `~astropy_feedrot.visibilities.poles`).
    feeds : `~astropy_feedrot.Receptors` or mapping, optional
        Receptors for antennas the file gives none or unusable ones (all
        antennas, or ``{antenna number or name: Receptors}``;
        `~astropy_feedrot.visibilities.with_receptors`). A Measurement
        Set's ``FEED`` receptors are replaced by them.
    mounts : {'file', 'catalogue'}, optional
        Whose mount and focus an antenna within
        `~astropy_feedrot.visibilities.CATALOGUE_TOLERANCE` of a station of
        ``catalogue`` takes where the two differ: the file's (default) or
        the catalogue's (`~astropy_feedrot.visibilities.catalogue_mounts`;
        an antenna whose mount label has no model takes its station's).
    catalogue : `~astropy_feedrot.stations.StationCatalogue`, path or False, optional
        The station catalogue: the mounts are compared with it, antennas
        without receptors take its receptors
        (`~astropy_feedrot.visibilities.catalogue_receptors`), and a
        telescope it holds as fixed to the ground is an aperture array. The
        embedded one by default, another, or False for none.
    ionosphere : `~astropy_feedrot.ionosphere.Ionosphere`, optional
        Remove (apply) the ionospheric Faraday rotation too, in the same
        pass, per antenna, epoch and channel (:doc:`/ionosphere`).
    redo : bool, optional
        Correct data whose history says they were corrected in that
        direction already, or compute again an output that holds this
        correction already.

    Raises
    ------
    ValueError
        For an option outside its choices.
    TypeError
        For an ``ionosphere`` that is no
        `~astropy_feedrot.ionosphere.Ionosphere`.

    Notes
    -----
    What every correction of data refuses, before anything is written: an
    aperture array; antennas whose mount label has no model (orbiting ones
    aside) or whose receptors cannot be used (unless ``feeds`` gives them),
    all named in one message with their reasons; data whose history says
    they were corrected already (unless ``redo``); an ``ionosphere`` that
    does not cover the epochs, or a table of rotation measures that lacks an
    antenna (`~astropy_feedrot.ionosphere.IonosphereError`).

    What every correction warns, once each: ``CatalogueMountWarning`` if the
    file's mount or focus of some antennas differs from their catalogue
    station's (naming them with both); ``CatalogueReceptorsWarning`` if some
    antennas took their receptors from the catalogue;
    ``UncorrectedBaselinesWarning`` if some rows are on baselines to an
    orbiting antenna (left as they were, the others corrected);
    ``DegenerateGeometryWarning``, with the count, if the feed rotation is
    undefined in some rows (an alt-az antenna at the zenith).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.visibilities import Correction
    >>> correction = Correction(convention="casa")
    >>> correction.vertical, correction.pole
    ('geocentric', 'casa')
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "corrected.idifits"
    >>> correction.correct(sample_file("difx_k08161.idifits"), out).name
    'corrected.idifits'
    """

    def __init__(self, *, direction="remove", frame="apparent", convention="rigorous",
                 vertical=None, pole=None, feeds=None, mounts="file", catalogue=None,
                 ionosphere=None, redo=False):
        self.vertical, self.pole = convention_options(convention, vertical, pole)
        if self.vertical not in VERTICALS:
            raise ValueError(f"vertical must be one of {VERTICALS}, got {vertical!r}")
        if self.pole not in POLES:
            raise ValueError(f"pole must be one of {POLES}, got {pole!r}")
        self.direction = check_direction(direction)
        self.mounts = check_mounts_option(mounts)
        self.ionosphere = check_ionosphere(ionosphere)
        self.convention, self.frame, self.feeds = convention, frame, feeds
        self.catalogue, self.redo = catalogue, bool(redo)

    @classmethod
    def of(cls, correction=None, **options):
        """``correction`` itself, or one made of ``options`` (not both).

        Examples
        --------
        >>> from astropy_feedrot.visibilities import Correction
        >>> Correction.of(direction="apply").direction
        'apply'
        """
        if correction is None:
            return cls(**options)
        if not isinstance(correction, cls):
            raise TypeError(f"correction must be a Correction, got {type(correction).__name__}")
        if options:
            raise TypeError(f"give the options {sorted(options)} to the Correction, or no "
                            "Correction")
        return correction

    def __repr__(self):
        return (f"Correction(direction={self.direction!r}, frame={self.frame!r}, "
                f"vertical={self.vertical!r}, pole={self.pole!r}, mounts={self.mounts!r})")

    @property
    def frame_name(self):
        """The frame as the history names it."""
        frame = self.frame
        return frame if isinstance(frame, str) else getattr(frame, "name", type(frame).__name__)

    # --- the steps every format takes -----------------------------------------------------

    def refuse_aperture_array(self, telescope, where):
        """Refuse an aperture array's data before anything is read or written
        (`~astropy_feedrot.visibilities.resolve.refuse_aperture_array`)."""
        refuse_aperture_array(telescope, self.catalogue, where=where)

    def resolve(self, antennas, telescope, where, *, numbers=None):
        """The file's antennas as the correction uses them
        (`~astropy_feedrot.visibilities.resolve.resolve_antennas`)."""
        return resolve_antennas(antennas, telescope=telescope, mounts=self.mounts,
                                catalogue=self.catalogue, feeds=self.feeds, numbers=numbers,
                                where=where)

    def usable(self, antennas, numbers, where, error=ValueError):
        """The antennas the rows use that can be corrected, and the orbiting ones
        (`~astropy_feedrot.visibilities.unusable.usable_antennas`); the refusal
        raised as ``error``."""
        try:
            return usable_antennas(antennas, numbers, where)
        except ValueError as refusal:
            if error is ValueError:
                raise
            raise error(str(refusal)) from None

    def check_history(self, text, where, *, what=None):
        """Refuse data whose history says they were corrected in this direction already
        (unless ``redo``)."""
        check_history(text, self.direction, where, redo=self.redo, what=what)

    def history(self, what):
        """The history line of this correction of ``what``."""
        return history_entry(self.direction, what, frame=self.frame_name,
                             vertical=self.vertical)

    def ionosphere_text(self, before=""):
        """What the history says of the ionosphere ('' without one)."""
        return "" if self.ionosphere is None else ionosphere_text(self.ionosphere, before)

    def pole_context(self):
        """The context in which angles are measured from this correction's pole."""
        return pole_context(self.pole)

    # --- files of every kind -------------------------------------------------------------

    def correct(self, path, output=None, **options):
        """Correct a file of any kind: into ``output``, or in place (None).

        Parameters
        ----------
        path : str or path-like
            A file of any kind of `~astropy_feedrot.visibilities.FILE_KINDS`.
        output : str or path-like, optional
            The copy to write (see `~astropy_feedrot.visibilities.correct_file`);
            None corrects a Measurement Set or an MSv4 processing set in
            place.
        **options
            The adapter's own: ``overwrite``, ``progress``, ``client``; a
            Measurement Set's ``data_column``, ``corrected_column``,
            ``overwrite_column``.

        Returns
        -------
        pathlib.Path
            What was written.

        Raises
        ------
        FileNotFoundError, FileExistsError, ValueError
            Before anything is read but the file's telescope name: a missing
            input, an output of the wrong format, the input as output, an
            existing output without ``overwrite``, an output in no
            directory, an aperture array; then what the adapter refuses.
        """
        source = existing_path(path)
        kind = file_kind(source)
        adapter = adapter_of(kind)
        if output is not None:  # before any work
            check_output_format(kind, output)
            check_output_path(source, output, options.get("overwrite", False))
        self.refuse_aperture_array(adapter.telescopes(source), str(source))
        return adapter.correct(self, source, output, **options)
