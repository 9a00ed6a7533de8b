"""Errors raised by springlab.

``SpringlabError`` is the root and a ``ValueError``, so callers that catch
``ValueError`` for bad input also catch every springlab error::

    SpringlabError (ValueError)          bad input: names the parameter, its value, what to do
    |-- UnbalanceableError               a configuration or design cannot balance the arm (a proof)
    |-- SearchExhaustedError             a search ran out of starts, configurations or time: not a proof
    |-- GeometryError                    attachment points, reach, a linkage that cannot close
    |   `-- AttachmentError (also an UnbalanceableError)  a spring end off its link
    |-- LineChainError                   an arm is not one of the papers' line chains (the general model takes it)
    |-- UpAdviceError                    a URDF refused as a line chain that another up direction reads
    `-- SolverError (also RuntimeError)  a numerical solver or a simulation model failed
"""


class SpringlabError(ValueError):
    """Bad input to springlab: the message names the parameter and its value."""


class UnbalanceableError(SpringlabError):
    """A spring configuration or design cannot balance the arm; the message says why."""


class SearchExhaustedError(SpringlabError):
    """A search (random starts, configurations, a time limit) ended without a design. This
    is not a proof that none exists: the message names the limits it ran under and what to
    raise to search further."""


class GeometryError(SpringlabError):
    """An attachment, a spring's reach or a linkage's closure is geometrically impossible."""


class AttachmentError(GeometryError, UnbalanceableError):
    """A spring end lies off its link or needs a longer bracket than allowed: the design
    with these attachments cannot be built (a search moves on to other attachments)."""


class LineChainError(SpringlabError):
    """An arm (read from a URDF) is not one of the papers' idealised chains, whose links lie on one
    line at zero angles with their centres of mass on them: an offset shoulder, a centre of mass off
    its link, two joints at one point that are no wrist. The general model
    (:func:`springlab.model.urdf.read_revolute_chain`, :mod:`springlab.design.arms`) takes such an arm."""


class UpAdviceError(SpringlabError):
    """A URDF refused as a line chain with the up direction it was read with, which another up reads:
    the message names that ``--up``. ``springlab design`` designs the file on the general model only when
    the up was given (the user vouches for it), never on a guess."""


class MeshError(SpringlabError):
    """A mesh a URDF names could not be found (``found`` False) or read: the message names the file."""

    def __init__(self, message: str, *, filename: str = "", found: bool = True):
        super().__init__(message)
        self.filename, self.found = filename, found


class SolverError(SpringlabError, RuntimeError):
    """A solver (linear programme, multibody model, browser) failed where it should not;
    the message names the solver and its status."""
