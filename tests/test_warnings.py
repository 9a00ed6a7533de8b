import warnings

import pytest


def test_deprecations_from_springlab_are_errors():
    # pyproject's filterwarnings turns a DeprecationWarning attributed to springlab into an error
    with pytest.raises(DeprecationWarning):
        warnings.warn_explicit("old call", DeprecationWarning, "springlab/chain.py", 1,
                               module="springlab.model.chain")
