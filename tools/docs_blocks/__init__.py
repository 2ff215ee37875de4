"""The generated passages of the docs, one module per source: each module's ``BLOCKS`` says how its blocks are made,
and ``tools/docs_numbers.py`` puts them together, finds them in the documents and writes them."""
