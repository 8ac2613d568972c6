"""Writers: DXF, charts, report.  Only this stage imports ezdxf and matplotlib."""
