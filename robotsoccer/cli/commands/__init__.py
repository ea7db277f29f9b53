"""The commands, one module per command, each with its parser and its function.

Each module has its ``add_parser`` and its ``cmd_*`` function; :data:`robotsoccer.cli.COMMANDS`
maps names to the functions and :data:`robotsoccer.cli.parser.COMMAND_MODULES` lists the
modules.
"""
