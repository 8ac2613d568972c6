"""Writers: DXF, SVG, charts, report.  Only this stage imports ezdxf and matplotlib."""
