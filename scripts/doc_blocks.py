"""Reading the ``` blocks of doc/architecture.md that the layout checks hold to the code."""


def block_after(doc_text, heading):
    """(line number, text) of each line of the first ``` block after the line `heading` (its
    stripped text), or None when there is no such heading or another heading comes first."""
    lines = doc_text.split('\n')
    start = next((i for i, line in enumerate(lines) if line.strip() == heading), None)
    if start is None:
        return None
    block, inside = [], False
    for i in range(start + 1, len(lines)):
        line = lines[i]
        if line.startswith('#') and not inside:
            return None  # the next heading came before a table
        if line.startswith('```'):
            if inside:
                return block
            inside = True
        elif inside:
            block.append((i + 1, line))
    return None
