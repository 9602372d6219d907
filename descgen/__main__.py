from descgen.cli import entry

entry()
