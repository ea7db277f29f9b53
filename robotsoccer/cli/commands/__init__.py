"""One module per group of commands; :data:`robotsoccer.cli.COMMANDS` maps names to them."""
