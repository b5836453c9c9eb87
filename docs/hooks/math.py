"""MkDocs hook: display equations typeset at build time.

A block between lines holding only ``$$`` is LaTeX; it becomes MathML (latex2mathml, from
PyPI), which browsers render natively, so the guide loads no script and no font from anywhere.
An equation latex2mathml cannot read fails the build, naming the page and the equation.
"""

import html
import re

from latex2mathml.converter import convert
from mkdocs.exceptions import PluginError

BLOCK = re.compile(r"^\$\$[ \t]*\n(.*?)\n\$\$[ \t]*$", re.MULTILINE | re.DOTALL)


def on_page_markdown(markdown, page, **kwargs):
    def typeset(match):
        tex = match.group(1).strip()
        try:
            mathml = convert(tex, display="block")
        except Exception as error:  # latex2mathml raises several kinds
            raise PluginError(
                f"{page.file.src_uri}: the equation `{tex[:60]}` cannot be typeset: {error}"
            ) from error
        # The LaTeX stays with the MathML as its annotation (shown by no browser; kept for
        # copying and for tools that read the source).
        opening, rest = mathml.split(">", 1)
        body = rest.removesuffix("</math>")
        annotation = f'<annotation encoding="application/x-tex">{html.escape(tex)}</annotation>'
        return (f'<div class="equation">{opening}><semantics><mrow>{body}</mrow>{annotation}'
                "</semantics></math></div>")

    return BLOCK.sub(typeset, markdown)
