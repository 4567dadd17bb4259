"""``python -m powergraph ...``: the same command line as the ``powergraph`` script."""
from powergraph.cli.main import main

if __name__ == "__main__":
    main()
