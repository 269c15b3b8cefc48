"""What vulture (the dead-code finder) cannot see used inside the package, kept on purpose.

Read by vulture, never imported (an attribute set in ``__init__`` is not on its class):
``vulture planmethod vulture_whitelist.py --min-confidence 60`` reports nothing, and
``tests/test_dead_code.py`` runs exactly that. A name goes here only with the reason it stays.
"""

from planmethod import __dir__, __getattr__
from planmethod.application.api import Exercise
from planmethod.application.tasks import Watch
from planmethod.cli import _Parser
from planmethod.grading.templates import variant_exercise
from planmethod.kinematics.motion import Motion
from planmethod.kinematics.program import Model
from planmethod.studio.server import StudioHandler, StudioServer, _DeadlineReader
from planmethod.testing.pseudo import _PageText

# argparse's parser reads this attribute: negative numbers in any float notation are values
_Parser._negative_number_matcher  # noqa: B018
# how many programs a mechanism's model compiled: what tests and benchmarks ask of the cache
Model.compilations  # noqa: B018
# a material point's velocity and acceleration by its local coordinates: the public API of a
# solve, beside velocity(point) for named points (tests/test_properties.py)
Motion.velocity_of  # noqa: B018
Motion.acceleration_of  # noqa: B018
# a variant posed at another crank angle on its followed assembly: the public API the
# continuation tests call (tests/test_continuation.py)
variant_exercise  # noqa: B018
# the standard library's HTTP server reads these class attributes and calls these methods by
# name (socketserver, http.server): the studio's server and its request handler
StudioServer.daemon_threads  # noqa: B018
StudioServer.allow_reuse_address  # noqa: B018
StudioServer.request_queue_size  # noqa: B018
StudioServer.handle_error  # noqa: B018
StudioHandler.server_version  # noqa: B018
StudioHandler.sys_version  # noqa: B018
StudioHandler.protocol_version  # noqa: B018
StudioHandler.timeout  # noqa: B018
StudioHandler.do_GET  # noqa: B018
StudioHandler.do_POST  # noqa: B018
StudioHandler.do_PUT  # noqa: B018
StudioHandler.do_DELETE  # noqa: B018
StudioHandler.do_HEAD  # noqa: B018
StudioHandler.log_message  # noqa: B018
StudioHandler.log_error  # noqa: B018
StudioHandler.close_connection  # noqa: B018
# the standard library's HTML parser calls these methods by name (html.parser): the
# pseudo-translation's reader of a page's visible text
_PageText.handle_starttag  # noqa: B018
_PageText.handle_endtag  # noqa: B018
_PageText.handle_data  # noqa: B018
# the io module's buffered reader calls a raw stream's readinto by name: the studio's reader
# that keeps a request's deadline
_DeadlineReader.readinto  # noqa: B018
# Python calls a module's __getattr__ and __dir__ by name: the top level reaches the Python
# API lazily (planmethod.load …, docs/api.md)
__getattr__  # noqa: B018
__dir__  # noqa: B018
# the Python API's own methods and properties, which scripts and notebooks call
# (docs/api.md, tests/test_api.py)
Exercise.is_template  # noqa: B018
Exercise.workbook  # noqa: B018
Watch.cancelled  # noqa: B018
