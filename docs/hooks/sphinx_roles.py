"""A griffe extension for the Python API reference (docs/guide/api-python.md): the package's
docstrings are written for ``help()`` and Sphinx, with roles such as :meth:`preset`; in the
Markdown reference a role becomes code, so the text reads the same in both places."""

import re

import griffe

ROLE = re.compile(r":(?:meth|attr|class|func|mod|data|obj|exc):`~?([^`]+)`")


class SphinxRoles(griffe.Extension):
    def on_instance(self, *, obj, **kwargs):
        if obj.docstring is not None:
            obj.docstring.value = ROLE.sub(lambda m: f"`{m.group(1)}`", obj.docstring.value)
