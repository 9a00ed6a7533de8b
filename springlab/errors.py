"""Errors raised by springlab. All are ``ValueError`` subclasses, so callers that
catch ``ValueError`` for bad input also catch these."""


class SpringlabError(ValueError):
    """Bad input to springlab: the message names the parameter and its value."""


class UnbalanceableError(SpringlabError):
    """A spring configuration or design cannot balance the arm; the message says why."""
