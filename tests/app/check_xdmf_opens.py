"""ParaView opens the app's output: the volume mesh and the contact surface have the expected numbers of cells
and carry their arrays. usage: pvbatch check_xdmf_opens.py <output-dir>"""
import os
import sys

from paraview.simple import Xdmf3ReaderS

directory = sys.argv[1]
volume = Xdmf3ReaderS(FileName=[os.path.join(directory, 'mesh.xmf')])
volume.UpdatePipeline()
contact = Xdmf3ReaderS(FileName=[os.path.join(directory, 'mesh_contact.xmf')])
contact.UpdatePipeline()
summary = dict(line.strip().split(',') for line in open(os.path.join(directory, 'mesh_summary.csv')))
cells = volume.GetDataInformation().GetNumberOfCells()
faces = contact.GetDataInformation().GetNumberOfCells()
part_range = volume.GetCellDataInformation().GetArray('part').GetRange()
assert cells == int(summary['elements_total']), (cells, summary['elements_total'])
assert faces == int(summary['contact_elements']), (faces, summary['contact_elements'])
assert part_range == (0.0, 3.0), part_range
bounds = contact.GetDataInformation().GetBounds()
assert abs(bounds[4]) < 1e-9 and abs(bounds[5]) < 1e-9, bounds   # the contact surface is at Z = 0
print('ParaView read', cells, 'hexahedra and', faces, 'contact faces')
