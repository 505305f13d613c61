"""Renders a spatula mesh (mesh.xmf written by the app) to one PNG: side, top and bottom views of the full
spatula (the half mesh and its mirror image) coloured by part, like the paper's Figs. 2-3. Headless:

    scripts/render.sh scripts/render_mesh.py <output-dir>/mesh.xmf <picture.png>
"""
import os
import sys
import tempfile

from paraview.simple import (ColorBy, CreateView, GetColorTransferFunction, Reflect, Render,
                             SaveScreenshot, Show, Text, Xdmf3ReaderS)
from paraview.simple import _DisableFirstRenderCameraReset
from PIL import Image

_DisableFirstRenderCameraReset()

xmf, png = os.path.abspath(sys.argv[1]), sys.argv[2]  # the reader resolves mesh.h5 from an absolute path only
reader = Xdmf3ReaderS(FileName=[xmf])
full = Reflect(Input=reader, Plane='Y Min', CopyInput=1)
full.UpdatePipeline()

views = (('side view (from -Y)', (0, -1, 0), (0, 0, 1), 1.0), ('top view (from +Z)', (0, 0, 1), (0, 1, 0), 1.0),
         ('bottom view of the pad (from -Z)', (0, 0, -1), (0, 1, 0), 1.8))
pictures = []
for title, direction, up, zoom in views:
    view = CreateView('RenderView')
    view.ViewSize = [1600, 480]
    if hasattr(view, 'UseColorPaletteForBackground'):
        view.UseColorPaletteForBackground = 0
    view.Background = [1, 1, 1]
    view.OrientationAxesVisibility = 1
    display = Show(full, view)
    display.SetRepresentationType('Surface With Edges')
    display.EdgeColor = [0.1, 0.1, 0.1]
    ColorBy(display, ('CELLS', 'part'))
    display.SetScalarBarVisibility(view, False)
    lookup = GetColorTransferFunction('part')
    lookup.ApplyPreset('Jet', True)
    lookup.RescaleTransferFunction(0.0, 3.0)
    label = Text(Text=title + '   colours: P_I blue, P_II cyan, P_III yellow, P_IV red')
    label_display = Show(label, view)
    label_display.Color = [0, 0, 0]
    label_display.FontSize = 14
    view.CameraViewUp = list(up)
    view.CameraParallelProjection = 1
    view.CameraFocalPoint = [-150, 0, 40] if zoom == 1.0 else [150, 0, 0]
    view.CameraPosition = [view.CameraFocalPoint[i] + 3000 * direction[i] for i in range(3)]
    view.CameraParallelScale = 175 / zoom
    Render(view)
    picture = os.path.join(tempfile.mkdtemp(), 'view.png')
    SaveScreenshot(picture, view, ImageResolution=[1600, 480])
    pictures.append(Image.open(picture))

sheet = Image.new('RGB', (1600, 480 * len(pictures)), 'white')
for i, picture in enumerate(pictures):
    sheet.paste(picture, (0, 480 * i))
sheet.save(png)
print('wrote', png)
