"""Renders deformed states of a run (mesh_states.xmf written by the app) to one PNG: a side view of the full
spatula (the half mesh and its mirror image) per state, coloured by the first stress invariant I1 = tr(sigma) / E, like the paper's Figs. 5 and 7.
The states' times are the load parameter (theta_y in degrees for a rotation, u_z in nm for a lift). Headless:

    scripts/render.sh scripts/render_states.py <output-dir>/mesh_states.xmf <picture.png> [time ...]

Without times, up to four states spread over the run are drawn; with times, the states nearest to them.
"""
import os
import sys
import tempfile

from paraview.simple import (ColorBy, CreateView, GetColorTransferFunction, GetScalarBar, Reflect, Render, SaveScreenshot, Show,
                             Text, Xdmf3ReaderS)
from paraview.simple import _DisableFirstRenderCameraReset
from PIL import Image

_DisableFirstRenderCameraReset()

xmf, png = os.path.abspath(sys.argv[1]), sys.argv[2]  # the reader resolves mesh.h5 from an absolute path only
reader = Xdmf3ReaderS(FileName=[xmf])
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues) if hasattr(reader.TimestepValues, '__len__') else [reader.TimestepValues]
if not times:
    sys.exit(f'{xmf}: no states')
if len(sys.argv) > 3:
    chosen = [min(times, key=lambda t: abs(t - float(wanted))) for wanted in sys.argv[3:]]
else:
    count = min(4, len(times))
    chosen = [times[round(i * (len(times) - 1) / max(count - 1, 1))] for i in range(count)]
full = Reflect(Input=reader, Plane='Y Min', CopyInput=1)
largest = 1e-6
for time in chosen:  # one symmetric colour scale for all panels
    full.UpdatePipeline(time)
    largest = max(largest, *(abs(v) for v in full.CellData['I1'].GetRange()))
largest *= 0.5  # a few elements at the pad's bend carry the extremes; saturate them to show the rest

width, height = 1400, 520
pictures = []
for time in chosen:
    full.UpdatePipeline(time)
    view = CreateView('RenderView')
    view.ViewSize = [width, height]
    view.ViewTime = time
    if hasattr(view, 'UseColorPaletteForBackground'):
        view.UseColorPaletteForBackground = 0
    view.Background = [1, 1, 1]
    view.OrientationAxesVisibility = 1
    display = Show(full, view)
    display.SetRepresentationType('Surface With Edges')
    display.EdgeColor = [0.2, 0.2, 0.2]
    display.Ambient, display.Diffuse = 1.0, 0.0  # flat colours: the scale reads the same on every face
    ColorBy(display, ('CELLS', 'I1'))
    lookup = GetColorTransferFunction('I1')
    lookup.ApplyPreset('Cool to Warm', True)
    lookup.RescaleTransferFunction(-largest, largest)
    display.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lookup, view)
    bar.Title, bar.ComponentTitle = 'I1', ''
    bar.TitleColor = bar.LabelColor = [0, 0, 0]
    label = Text(Text=f'state at load parameter {time:.2f}   (side view from -Y, colour: I1 = tr(sigma) / E)')
    label_display = Show(label, view)
    label_display.Color = [0, 0, 0]
    label_display.FontSize = 14
    bounds = full.GetDataInformation().GetBounds()
    centre = [(bounds[0] + bounds[1]) / 2, 0.0, (bounds[4] + bounds[5]) / 2]
    view.CameraViewUp = [0, 0, 1]
    view.CameraParallelProjection = 1
    view.CameraFocalPoint = centre
    view.CameraPosition = [centre[0], centre[1] - 4000, centre[2]]
    view.CameraParallelScale = 0.6 * max(bounds[5] - bounds[4], (bounds[1] - bounds[0]) * height / width)
    Render(view)
    picture = os.path.join(tempfile.mkdtemp(), 'view.png')
    SaveScreenshot(picture, view, ImageResolution=[width, height])
    pictures.append(Image.open(picture))

sheet = Image.new('RGB', (width, height * len(pictures)), 'white')
for i, picture in enumerate(pictures):
    sheet.paste(picture, (0, height * i))
sheet.save(png)
print('wrote', png, 'with states at', ', '.join(f'{t:.2f}' for t in chosen))
