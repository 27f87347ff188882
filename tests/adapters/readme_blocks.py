"""The README's code blocks, for the tests that run them as a reader would."""
import os
import re
import textwrap

README = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "README.md")


def readme_python_block(containing):
    """The README's ```python block that contains `containing`, dedented."""
    with open(README, encoding="utf-8") as readme:
        blocks = re.findall(r"^( *)```python\n(.*?)^\1```", readme.read(), re.M | re.S)
    matches = [textwrap.dedent(body) for _, body in blocks if containing in body]
    assert len(matches) == 1, "README.md has %d python blocks with %r" % (len(matches), containing)
    return matches[0]
