import vtk
pts = [(0,0,0),(1,0,0),(0,1,0),(0,0,1),(1,1,1)]
g = vtk.vtkUnstructuredGrid()
p = vtk.vtkPoints(); p.SetDataTypeToDouble()
for x in pts: p.InsertNextPoint(*x)
g.SetPoints(p)
for t in [(0,1,2,3),(1,2,3,4)]:
    ids = vtk.vtkIdList()
    for i in t: ids.InsertNextId(i)
    g.InsertNextCell(vtk.VTK_TETRA, ids)
m = vtk.vtkDoubleArray(); m.SetName('moisture')
for v in [0.1, 0.2, 0.3, 0.4, 0.5]: m.InsertNextValue(v)
g.GetPointData().AddArray(m)
d = vtk.vtkFloatArray(); d.SetName('displacement'); d.SetNumberOfComponents(3)
for i in range(5): d.InsertNextTuple3(i * 0.5, -i, 0.25)
g.GetPointData().AddArray(d)
l = vtk.vtkIntArray(); l.SetName('label')
for v in [0, 1]: l.InsertNextValue(v)
g.GetCellData().AddArray(l)
s = vtk.vtkDoubleArray(); s.SetName('shrinkage')
for v in [0.125, 0.75]: s.InsertNextValue(v)
g.GetCellData().AddArray(s)
for name, mode, comp, hdr in [('vtk_ascii', 'ascii', False, 64), ('vtk_binary_zlib_uint32', 'binary', True, 32),
                              ('vtk_appended_raw', 'appended', False, 64), ('vtk_appended_zlib', 'appended', True, 64),
                              ('vtk_appended_base64', 'appended64', False, 64),
                              ('vtk_appended_base64_zlib_uint32', 'appended64', True, 32)]:
    w = vtk.vtkXMLUnstructuredGridWriter()
    w.SetFileName(name + '.vtu'); w.SetInputData(g)
    {'ascii': w.SetDataModeToAscii, 'binary': w.SetDataModeToBinary, 'appended': w.SetDataModeToAppended,
     'appended64': w.SetDataModeToAppended}[mode]()
    w.SetEncodeAppendedData(mode == 'appended64')  # VTK's default is base64-encoded appended data
    w.SetCompressorTypeToZLib() if comp else w.SetCompressorTypeToNone()
    w.SetHeaderTypeToUInt64() if hdr == 64 else w.SetHeaderTypeToUInt32()
    w.Write()
