#include <pipeline/sort_check.h>

namespace tr {

Result<SortCheckReport> check_sorts(Pipeline& pipeline, const SceneVolume& volume,
                                    const SortCheckOptions& options,
                                    const std::function<void(const SortCheckMethod&)>& on_method,
                                    const std::function<void(const SortCheckRow&)>& on_row) {
    TR_TRY(const std::shared_ptr<const LoadedMesh> loaded, pipeline.mesh(volume));
    const Bounds3 bounds = loaded->tets.bounds();
    SortCheckReport report;
    for (SortMethod method : options.methods) {
        SortCheckMethod summary{method, {}, 0};
        TR_TRY(summary.prepared, pipeline.prepared_sort(volume, method));
        if (on_method) on_method(summary);
        for (int v = 0; v < options.views; ++v) {
            const Camera camera =
                random_view(bounds, options.seed * 7919 + static_cast<std::uint64_t>(v),
                            options.orthographic, options.inside);
            const CameraFrame frame(camera, options.width, options.height);
            TR_TRY(const ViewOrder view, pipeline.visibility_order(volume, frame, method));
            SortCheckRow row;
            row.method = method;
            row.view = v;
            row.claims_exact = view.prepared.exact;
            row.convexified = view.prepared.sorted->convexified;
            row.stats = view.stats;
            row.check = check_order(view.prepared.mesh(), view.order, frame);
            summary.violations += row.check.violations;
            if (on_row) on_row(row);
            report.rows.push_back(row);
        }
        if (summary.prepared.exact && summary.violations > 0) report.exact_violated = true;
        report.methods.push_back(std::move(summary));
    }
    return report;
}

}  // namespace tr
