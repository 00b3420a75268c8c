# VTK module, Python package and ParaView plugin (added by its owner)
