"""Words: every sentence a person reads, as a message template with named fields, rendered in
one place in the course's language.

* :mod:`planmethod.words.message` — :class:`Message`, :func:`message`, :func:`plural`: a
  sentence as data;
* :mod:`planmethod.words.language` — which language is spoken (``--lang``, ``[course]
  language``, ``PLANMETHOD_LANG``) and its gettext catalogue;
* :mod:`planmethod.words.render` — :func:`render`, the one function that makes text.

This package imports nothing of planmethod's and nothing outside the standard library: every
layer may make messages, and ``import planmethod`` stays light (a catalogue is read the first
time its language speaks).

Examples
--------
>>> from planmethod.words import message, render, speaking
>>> render(message("{count} draws rejected", count=4))
'4 draws rejected'
"""

from .language import current, speaking
from .message import Message, message, plural, template
from .render import number_text, render

__all__ = ["Message", "current", "message", "number_text", "plural", "render", "speaking",
           "template"]
