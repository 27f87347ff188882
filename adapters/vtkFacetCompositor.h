/**
 * @class   vtkFacetCompositor
 * @brief   Private: vtkFacetRenderFilter on the processes of a vtkMultiProcessController:
 *          one camera for all of them, and their pieces' images composited by depth with IceT.
 *
 * Each process renders the piece of the input it holds, with the same camera and lights
 * (a camera fitted to the input is fitted to the union of all pieces' bounds), and the
 * images are merged by depth (sort-last compositing, IceT's z-buffer mode) onto one process,
 * the target, or onto every process. Opaque surfaces composite exactly: a pixel shows the
 * nearest polygon of all pieces, as if one process had rendered the whole input.
 *
 * Every process calls Prepare, then Composite, once per execution, whatever happened to it:
 * both are collective. A process whose input is bad (or whose render failed) takes part
 * with an empty image, so the others never wait for a call that will not come; the target
 * names it in a warning.
 *
 * What goes through IceT. In z-buffer mode IceT keeps, at every pixel, the "color" of the
 * smaller depth and treats depth 1 as background (not sent); it copies colors, never blends
 * them (IceT's cc_composite_func_body.h, compress_func_body.h). So an RGBA_FLOAT color
 * carries 16 bytes of ours per pixel, their bits untouched: the RGBA bytes, the rank and
 * the 64-bit CellId, or with the error estimate the RGBA bytes, a 16-bit rank, a 48-bit
 * CellId and the estimate's float (Settings::WithEstimate). The depth sent is the window
 * depth halved, exact for every float depth and order-preserving, so that a polygon at window
 * depth 1 (a tiny near plane rounds every depth to 1) is not taken for background.
 *
 * Ties. On equal depths IceT keeps the image that comes later in its compose order (the
 * comparison is `front < back ? front : back`); the order is set to ranks P-1, ..., 1, 0,
 * so the lowest rank wins, as the earlier polygon wins within one render (Conventions.h,
 * "Depth"): pieces that are consecutive cell ranges in rank order composite as one render.
 * Window depths are depth keys rounded once (monotone), so two pieces' surfaces closer than
 * that rounding tie here where one render would have compared their keys.
 *
 * Without IceT at build time (FACET_HAVE_ICET undefined), Composite leaves every process
 * with its own piece's image and says so once.
 */

#ifndef vtkFacetCompositor_h
#define vtkFacetCompositor_h

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <memory>
#include <string>

class vtkDataArray;
class vtkFacetIceT;
class vtkFacetImageRenderer;
class vtkFacetMessages;
class vtkFloatArray;
class vtkImageData;
class vtkMultiProcessController;
class vtkPolyData;

class vtkFacetCompositor
{
public:
  /// IceT's strategies for compositing one image (icetSingleImageStrategy).
  enum class Strategy
  {
    Automatic,
    BinarySwap,
    Tree,
    RadixK
  };

  struct Settings
  {
    int Width = 0;
    int Height = 0;
    int Target = 0;          ///< the rank that receives the image
    bool ToAllRanks = false; ///< every rank receives it
    Strategy Method = Strategy::Automatic;
    /// Composite each pixel's error estimate too: in the image's own payload (the rank in 16
    /// bits, the CellId in 48, the estimate's float in the 32 bits this frees) when every
    /// rank's cell ids fit and there are at most 65535 ranks; else in a second IceT
    /// composite of 8 bytes a covered pixel, with the same depths (the same rank wins).
    bool WithEstimate = false;
    /// Every CellId this rank labels a pixel with is in [0, 2^48): true for the piece's own
    /// cell ids (see CellIdsFit48Bits for global ids). Not required to agree: the ranks
    /// pack the estimate only if it holds on all of them.
    bool CellIdsFit48Bits = true;
  };

  vtkFacetCompositor();
  ~vtkFacetCompositor();
  vtkFacetCompositor(const vtkFacetCompositor&) = delete;
  vtkFacetCompositor& operator=(const vtkFacetCompositor&) = delete;

  /// Whether `controller` has more than one process (then a filter renders a piece).
  static bool IsParallel(vtkMultiProcessController* controller);

  /// Whether this build composites (IceT and VTK's ParallelMPI were found).
  static bool IsAvailable();

  /**
   * Collective, first: makes `bounds` the union of every process's bounds (uninitialized,
   * as vtkMath::UninitializeBounds, when no process has any), and checks that the processes
   * agree on `settings` (else an error on every process, and Composite merges nothing).
   */
  void Prepare(vtkMultiProcessController* controller,
    const Settings& settings,
    double bounds[6],
    vtkFacetMessages& messages);

  /// The input's global cell ids (vtkCellData::GetGlobalIds) if it has usable ones: one
  /// integer per cell; else none, with a warning if it has unusable ones.
  static vtkDataArray* GlobalIdsOf(vtkPolyData* input, vtkFacetMessages& messages);

  /// Whether every label of `globalIds` (GlobalIdsOf's; null: the piece's own cell ids)
  /// is in [0, 2^48), as Settings::CellIdsFit48Bits asks.
  static bool CellIdsFit48Bits(vtkDataArray* globalIds);

  /**
   * Labels the pixels [begin, end) of this process's render: RankId is this rank where a
   * cell shows (-1 elsewhere), and CellId becomes the cell's entry in `globalIds` when
   * given (one per input cell).
   */
  void LabelPixels(vtkDataArray* globalIds,
    vtkIdType* cellIds,
    int* rankIds,
    vtkIdType begin,
    vtkIdType end) const;

  /**
   * Collective, second: composites the processes' images (`rendered`: this process's image
   * is in `image`'s arrays; false after an error, it then adds nothing) into `output` on
   * the target (every process with ToAllRanks); the others' outputs keep their field data
   * but no pixels. Adds the composite's cost to the field data (`FacetCompositeSeconds`,
   * `FacetCompositeBytes`, `FacetCompositeStrategy`) and to the render plan. With
   * WithEstimate, `estimate` (this process's per-pixel error estimate, or null: zeros) becomes
   * on the target the estimate of the piece each pixel shows, 0 on the background.
   */
  void Composite(vtkFacetImageRenderer& image,
    vtkImageData* output,
    bool rendered,
    vtkFacetMessages& messages,
    vtkFloatArray* estimate = nullptr);

private:
  friend class vtkFacetIceT; // its composites add to a Cost
  /// What one composite cost this rank.
  struct Cost
  {
    double PackSeconds = 0.0;
    double IceTSeconds = 0.0; // icetCompositeImage
    double UnpackSeconds = 0.0;
    long long BytesSent = 0;      // by this rank, as IceT counts them
    long long BytesSentByAll = 0; // by every rank
    std::string Strategy;         // IceT's names: "(Sequential, Radix-k)"
  };

  bool Gather(bool rendered, vtkFacetMessages& messages);
  bool Receives() const { return this->Rank == this->Current.Target || this->Current.ToAllRanks; }
  void KeepOwnPieces(vtkFacetImageRenderer& image,
    vtkImageData* output,
    vtkFacetMessages& messages);
  void MakeEmpty(vtkImageData* output) const;
  // With IceT only:
  bool RunIceT(vtkFacetImageRenderer& image,
    bool rendered,
    vtkFloatArray* estimate,
    Cost& cost,
    vtkFacetMessages& messages);
  void Report(vtkFacetImageRenderer& image,
    vtkImageData* output,
    const Cost& cost,
    double seconds) const;

  vtkSmartPointer<vtkMultiProcessController> Controller;
  Settings Current;
  int Rank = 0;
  int Ranks = 1;
  bool Agreed = false;
  bool PackEstimate = false; // the estimate rides in the image's payload (Settings::WithEstimate)
  std::string FailedRanks;   // "1 and 3": ranks whose pieces are missing from the image

  std::unique_ptr<vtkFacetIceT> IceT; // with IceT: its context, buffers and composites
};

#endif
