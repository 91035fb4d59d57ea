"""The command lines' plumbing, importable from here: the error contract, chair loading and the shared options.

Topic modules: ``contract`` (the error contract: one line, exit status 2; ``run``), ``chairs`` (``--chair`` and
``--set``), ``options``
(the shared options), ``numbers`` (numeric options within their bounds), ``files`` (outputs checked before any
work, written all or none) and ``commands`` (the registry behind the ``stability`` console script).
"""

from stability.cli.contract import *  # noqa: F401,F403
from stability.cli.contract import __all__  # noqa: F401
